#include "steadylight/render.h"

#include <chrono>
#include <csignal>
#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include "steadylight/base/checkpoint.h"
#include "steadylight/base/error.h"
#include "steadylight/output/atomic_file.h"
#include "steadylight/output/console.h"
#include "steadylight/output/frame_layers.h"
#include "steadylight/output/frame_manifest.h"
#include "steadylight/output/frame_names.h"
#include "steadylight/output/image_writer.h"
#include "steadylight/output/interrupt.h"
#include "steadylight/output/settings_file.h"
#include "steadylight/output/video.h"

namespace steadylight {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

Scene load_scene(const RenderSettings& settings) {
    Scene scene(load_scene_desc(settings.scene_file));
    const SceneDesc& desc = scene.desc();
    scene.set_resolution(settings.width.value_or(desc.camera.width), settings.height.value_or(desc.camera.height));
    return scene;
}

/// A finished frame: the image, its layers for the EXR, and statistics when the method has any.
struct RenderedFrame {
    Image beauty;
    std::vector<std::pair<std::string, Image>> layers;
    std::optional<FrameStats> stats;
};

bool is_localized(const RenderSettings& settings) { return settings.method == "localized" || settings.method == "frozen"; }

LocalizedSettings localized_settings(const RenderSettings& settings) {
    LocalizedSettings localized = settings.localized;
    localized.base = settings.photon;
    localized.frozen = settings.method == "frozen";
    return localized;
}

/// `<out>/<scene>.irrcache`, or `--cache-file`; with several segments each gets its frames added:
/// `<scene>_0000-0029.irrcache`.
std::string cache_file_of(const RenderSettings& settings, const Scene& scene, const Segment& segment) {
    namespace fs = std::filesystem;
    fs::path file = settings.cache_file.empty() ? fs::path(settings.out_dir) / (scene.name() + ".irrcache")
                                                : fs::path(settings.cache_file);
    if (scene.segments().size() > 1)
        file.replace_filename(fmt::format("{}_{:04d}-{:04d}{}", file.stem().string(), segment.first, segment.last,
                                          file.extension().string()));
    return file.string();
}

/// The segment pass of `segment`, from its cache file when that matches.
StaticSolution static_solution(const RenderSettings& settings, const Scene& scene, RayTracer& tracer,
                               const Segment& segment) {
    const std::string file = cache_file_of(settings, scene, segment);
    StaticSolution solution = run_segment_pass(scene, tracer, segment.first, segment.last, localized_settings(settings), file);
    if (solution.loaded)
        spdlog::info("static cache: {} records loaded from {}", solution.records, file);
    else
        spdlog::info("static cache: {} records computed in {:.2f} s ({}), saved to {}", solution.records, solution.seconds,
                     solution.file_note, file);
    return solution;
}

RenderedFrame render_localized_frame(const RenderSettings& settings, const FrameContext& context,
                                     const StaticSolution& solution) {
    LocalizedFrame frame = render_localized(context, solution, localized_settings(settings));
    return {frame.beauty,
            {{"direct", std::move(frame.direct)},
             {"indirect", std::move(frame.indirect)},
             {"caustic", std::move(frame.caustic)},
             {"specular", std::move(frame.specular)},
             {"indirect_static", std::move(frame.indirect_static)},
             {"L_y", std::move(frame.L_y)},
             {"L_t", std::move(frame.L_t)},
             {"influence", std::move(frame.influence)},
             {"static_records", std::move(frame.static_records)},
             {"dynamic_records", std::move(frame.dynamic_records)}},
            frame.stats};
}

RenderedFrame render_frame(const RenderSettings& settings, const FrameContext& context, const StaticSolution* solution) {
    if (settings.method == "path") return {render_path_traced(context, settings.path), {}, std::nullopt};
    if (solution) return render_localized_frame(settings, context, *solution);
    PhotonFrame frame = render_photon_mapped(context, settings.photon);
    return {frame.beauty,
            {{"direct", std::move(frame.direct)},
             {"indirect", std::move(frame.indirect)},
             {"caustic", std::move(frame.caustic)},
             {"specular", std::move(frame.specular)},
             {"records", std::move(frame.records)}},
            frame.stats};
}

void write_frame(const RenderSettings& settings, const Scene& scene, int frame, const RenderedFrame& rendered) {
    const OutputSettings& output = settings.output;
    write_exr(frame_file_name(settings.out_dir, scene.name(), frame, "exr"),
              frame_exr_layers(rendered.beauty, rendered.layers), output.exr_type);
    write_png(frame_file_name(settings.out_dir, scene.name(), frame, "png"), rendered.beauty, output.view);
    if (settings.aov_pngs)
        for (const auto& [name, image] : rendered.layers)
            write_png(frame_file_name(settings.out_dir, scene.name(), frame, name + ".png"), image, output.view);
    if (rendered.stats)
        write_text_file(frame_file_name(settings.out_dir, scene.name(), frame, "stats.json"),
                        nlohmann::json(*rendered.stats).dump(2) + "\n");
}

/// Encodes the PNGs of the selected frames into `--video` (check_video_possible has accepted
/// `frames`). Frames skipped as complete from an earlier run have their PNGs already.
void write_video(const RenderSettings& settings, const Scene& scene, const std::vector<int>& frames) {
    const auto [first, last] = *contiguous_span(frames);
    encode_video({.out_dir = settings.out_dir, .scene_name = scene.name(), .first_frame = first,
                  .frame_count = last - first + 1, .fps = scene.desc().fps, .output = settings.output.video_file});
    spdlog::info("video: {} frames at {} fps written to {}", last - first + 1, scene.desc().fps, settings.output.video_file);
}

/// Writes `<out>/<scene>.settings.json` (an InputError if an earlier run used other settings,
/// unless --overwrite) and returns the settings key that frame manifests carry.
std::string record_settings(const RenderSettings& settings, const Scene& scene, const std::vector<int>& frames) {
    const Camera camera = scene.evaluate(0).camera;
    const RunInfo run{scene.name(), camera.width, camera.height, frames,
                      int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism))};
    const nlohmann::json json = make_settings_json(settings, run);
    write_settings_file(settings_file_name(settings.out_dir, scene.name()), json, settings.overwrite);
    return settings_key(json);
}

/// The selected frames whose outputs are not complete yet (all of them with --overwrite).
std::vector<int> frames_to_render(const RenderSettings& settings, const Scene& scene, const std::vector<int>& frames,
                                  const std::string& key, RenderSummary& summary) {
    if (settings.overwrite) return frames;
    std::vector<int> todo, complete;
    for (const int frame : frames) {
        const FrameCheck check = check_frame_outputs(settings.out_dir, scene.name(), frame, key);
        (check.complete ? complete : todo).push_back(frame);
        if (!check.problem.empty()) spdlog::info("frame {}: rendering it again: {}", frame, check.problem);
    }
    if (!complete.empty())
        spdlog::info("{} frame(s) complete from an earlier run, skipped: {} (--overwrite renders them again)",
                     complete.size(), format_frame_list(complete));
    summary.frames_skipped = int(complete.size());
    return todo;
}

/// write_frame, then the frame's manifest, which lists what write_frame wrote (last, so that a
/// frame cut short has none).
void write_frame_outputs(const RenderSettings& settings, const Scene& scene, int frame, const RenderedFrame& rendered,
                         const std::string& key) {
    std::error_code ignored;
    std::filesystem::remove(frame_manifest_name(settings.out_dir, scene.name(), frame), ignored);
    const WrittenFiles written;
    write_frame(settings, scene, frame, rendered);
    write_frame_manifest(settings.out_dir, scene.name(), frame, written.paths(), key);
}

/// Renders and writes `frames` (sorted) in order, adding each to `summary` when written.
/// Throws RenderInterrupted at the first checkpoint after Ctrl-C.
void render_frames(const RenderSettings& settings, const Scene& scene, const std::vector<int>& frames,
                   const std::string& key, RenderSummary& summary) {
    if (frames.empty()) return;
    // Build the acceleration structures once; each frame only moves the dynamic objects.
    RayTracer tracer(scene, scene.evaluate(frames.front()));
    const auto bsdfs = make_bsdfs(scene);
    std::optional<StaticSolution> solution;
    const Segment* solution_segment = nullptr;
    ConsoleProgress progress(int(frames.size()), settings.show_progress);
    const ScopedCheckpointListener listening(&progress);
    const std::optional<int> interrupt_after = test_interrupt_after_frames();
    for (const int frame : frames) {
        progress.begin_frame(frame);
        // Each segment's static pass runs (or is loaded) before its first selected frame.
        if (is_localized(settings) && solution_segment != &scene.segment_of(frame)) {
            solution_segment = &scene.segment_of(frame);
            solution = static_solution(settings, scene, tracer, *solution_segment);
        }
        if (interrupt_after == int(summary.frames_written.size())) std::raise(SIGINT);
        const Clock::time_point frame_start = Clock::now();
        const FrameState state = scene.evaluate(frame);
        tracer.set_frame(state);
        const LightSet lights(scene, state);
        const FrameContext context{scene, state, tracer, lights, bsdfs};
        const RenderedFrame rendered = render_frame(settings, context, solution ? &*solution : nullptr);
        write_frame_outputs(settings, scene, frame, rendered, key);
        summary.frames_written.push_back(frame);
        progress.finish_frame();
        spdlog::info("frame {:4d}  {:7.2f} s  {}{}", frame, seconds_since(frame_start),
                     frame_file_name(settings.out_dir, scene.name(), frame, "exr"),
                     rendered.stats ? "  |  " + summarize(*rendered.stats) : "");
    }
}

}  // namespace

RenderSummary render_animation(const RenderSettings& settings) {
    const Clock::time_point start = Clock::now();
    if (settings.method != "path" && settings.method != "photon" && !is_localized(settings))
        throw InputError("--method", "unknown method \"" + settings.method + "\" (localized, photon, frozen, path)");
    const Scene scene = load_scene(settings);
    const std::vector<int> frames = select_frames(settings.frames, scene.frame_count());
    if (!settings.output.video_file.empty()) check_video_possible(frames);  // before hours of rendering
    std::filesystem::create_directories(settings.out_dir);
    const std::string key = record_settings(settings, scene, frames);
    RenderSummary summary;
    const std::vector<int> todo = frames_to_render(settings, scene, frames, key, summary);
    try {
        render_frames(settings, scene, todo, key, summary);
    } catch (const RenderInterrupted&) {
        summary.interrupted = true;
    }
    summary.frames_left.assign(todo.begin() + long(summary.frames_written.size()), todo.end());
    // The video needs every selected frame: after an interrupt, the resumed run makes it.
    if (!settings.output.video_file.empty() && !summary.interrupted) write_video(settings, scene, frames);
    summary.seconds = seconds_since(start);
    return summary;
}

std::vector<std::string> bake_static_caches(const RenderSettings& settings) {
    const Scene scene = load_scene(settings);
    std::filesystem::create_directories(settings.out_dir);
    RayTracer tracer(scene, scene.evaluate(0));
    std::vector<std::string> files;
    for (const Segment& segment : scene.segments()) {
        static_solution(settings, scene, tracer, segment);
        files.push_back(cache_file_of(settings, scene, segment));
    }
    return files;
}

std::string describe_scene(const std::string& scene_file) {
    const Scene scene(load_scene_desc(scene_file));
    const SceneDesc& desc = scene.desc();
    std::string text = fmt::format("scene {} ({})\n", desc.name, scene_file);
    text += fmt::format("frames: {} at {} fps ({:.2f} s), {} segment(s)\n", desc.frame_count, desc.fps,
                        desc.frame_count / desc.fps, scene.segments().size());
    text += fmt::format("camera: {}x{}, vertical fov {} deg{}\n", desc.camera.width, desc.camera.height,
                        desc.camera.fov_y_deg, is_chain_animated(desc.camera.placement) ? ", animated" : "");
    long triangles = 0;
    int area_lights = 0;
    std::string objects;
    for (size_t i = 0; i < desc.objects.size(); ++i) {
        const ObjectDesc& object = desc.objects[i];
        const auto* mesh = std::get_if<TriangleMesh>(&object.geometry);
        const long count = mesh ? long(mesh->indices.size() / 3) : 0;
        triangles += count;
        area_lights += object.is_emitter();
        objects += fmt::format("  {:<20} {:<8} {:>8} {:<10} {}{}\n", object.name, object.is_dynamic() ? "dynamic" : "static",
                               mesh ? fmt::format("{} tris", count) : "sphere", desc.materials[size_t(object.material)].name,
                               object.is_emitter() ? "emitter" : "", object.marked_dynamic && !is_chain_animated(object.placement) ? " (marked)" : "");
    }
    text += fmt::format("objects: {} ({} static, {} dynamic), {} triangles\n", desc.objects.size(),
                        scene.static_objects().size(), scene.dynamic_objects().size(), triangles);
    text += objects;
    text += fmt::format("lights: {} area, {} point/spot\n", area_lights, desc.point_lights.size());
    for (const PointLightDesc& light : desc.point_lights)
        text += fmt::format("  {:<20} {}\n", light.name, light.type == PointLightType::point ? "point" : "spot");
    text += fmt::format("materials: {}\n", desc.materials.size());
    return text;
}

}  // namespace steadylight
