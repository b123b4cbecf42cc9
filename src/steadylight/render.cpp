#include "steadylight/render.h"

#include <chrono>
#include <filesystem>
#include <regex>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "steadylight/base/error.h"
#include "steadylight/output/atomic_file.h"
#include "steadylight/output/frame_layers.h"
#include "steadylight/output/frame_names.h"
#include "steadylight/output/image_writer.h"
#include "steadylight/output/progress.h"
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

FrameRange frames_to_render(const RenderSettings& settings, const Scene& scene) {
    const FrameRange range = settings.frames.value_or(FrameRange{0, scene.frame_count() - 1});
    if (range.last >= scene.frame_count())
        throw InputError("--frames", fmt::format("frame {} is past the scene's last frame {}", range.last,
                                                 scene.frame_count() - 1));
    return range;
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

RenderedFrame render_frame(const RenderSettings& settings, const FrameContext& context, Progress& progress,
                           const StaticSolution* solution) {
    if (settings.method == "path")
        return {render_path_traced(context, settings.path, [&](int done, int total) { progress.update_frame(done, total); }),
                {}, std::nullopt};
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

std::vector<int> frame_list(const FrameRange& range) {
    std::vector<int> frames;
    for (int frame = range.first; frame <= range.last; ++frame) frames.push_back(frame);
    return frames;
}

/// Encodes the frames' PNGs into `--video` (check_video_possible has accepted `frames`).
void write_video(const RenderSettings& settings, const Scene& scene, const std::vector<int>& frames) {
    const auto [first, last] = *contiguous_span(frames);
    encode_video({.out_dir = settings.out_dir, .scene_name = scene.name(), .first_frame = first,
                  .frame_count = last - first + 1, .fps = scene.desc().fps, .output = settings.output.video_file});
    spdlog::info("video: {} frames at {} fps written to {}", last - first + 1, scene.desc().fps, settings.output.video_file);
}

}  // namespace

FrameRange parse_frame_range(const std::string& text) {
    static const std::regex pattern(R"(\s*(\d+)\s*(?:-\s*(\d+)\s*)?)");
    std::smatch match;
    if (!std::regex_match(text, match, pattern) || match[1].length() > 9 || match[2].length() > 9)
        throw InputError("--frames", "expected a frame number N or a range A-B, got \"" + text + "\"");
    FrameRange range;
    range.first = std::stoi(match[1]);
    range.last = match[2].matched ? std::stoi(match[2]) : range.first;
    if (range.last < range.first)
        throw InputError("--frames", "range \"" + text + "\" ends before it starts");
    return range;
}

RenderSummary render_animation(const RenderSettings& settings) {
    const Clock::time_point start = Clock::now();
    if (settings.method != "path" && settings.method != "photon" && !is_localized(settings))
        throw InputError("--method", "unknown method \"" + settings.method + "\" (localized, photon, frozen, path)");
    const Scene scene = load_scene(settings);
    const FrameRange range = frames_to_render(settings, scene);
    const std::vector<int> frames = frame_list(range);
    if (!settings.output.video_file.empty()) check_video_possible(frames);  // before hours of rendering
    std::filesystem::create_directories(settings.out_dir);

    // Build the acceleration structures once; each frame only moves the dynamic objects.
    RayTracer tracer(scene, scene.evaluate(range.first));
    const auto bsdfs = make_bsdfs(scene);
    std::optional<StaticSolution> solution;
    const Segment* solution_segment = nullptr;
    Progress progress(range.last - range.first + 1, settings.show_progress);
    RenderSummary summary;
    for (int frame = range.first; frame <= range.last; ++frame) {
        // Each segment's static pass runs (or is loaded) before its first frame.
        if (is_localized(settings) && solution_segment != &scene.segment_of(frame)) {
            solution_segment = &scene.segment_of(frame);
            solution = static_solution(settings, scene, tracer, *solution_segment);
        }
        const Clock::time_point frame_start = Clock::now();
        const FrameState state = scene.evaluate(frame);
        tracer.set_frame(state);
        const LightSet lights(scene, state);
        const FrameContext context{scene, state, tracer, lights, bsdfs};
        const RenderedFrame rendered = render_frame(settings, context, progress, solution ? &*solution : nullptr);
        write_frame(settings, scene, frame, rendered);
        ++summary.frames_written;
        progress.finish_frame(fmt::format("frame {:4d}  {:7.2f} s  {}{}", frame, seconds_since(frame_start),
                                          frame_file_name(settings.out_dir, scene.name(), frame, "exr"),
                                          rendered.stats ? "\n  " + summarize(*rendered.stats) : ""));
    }
    if (!settings.output.video_file.empty()) write_video(settings, scene, frames);
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
