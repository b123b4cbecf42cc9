#include "steadylight/render.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <functional>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include "steadylight/base/atomic_file.h"
#include "steadylight/base/check.h"
#include "steadylight/base/checkpoint.h"
#include "steadylight/base/error.h"
#include "steadylight/base/stopwatch.h"
#include "steadylight/output/frame_layers.h"
#include "steadylight/output/frame_names.h"
#include "steadylight/output/image_writer.h"
#include "steadylight/output/video.h"
#include "steadylight/passes/frame_pass.h"
#include "steadylight/photons/distant_photon_share.h"
#include "steadylight/run/console.h"
#include "steadylight/run/frame_claim.h"
#include "steadylight/run/frame_manifest.h"
#include "steadylight/run/frame_writer.h"
#include "steadylight/run/interrupt.h"
#include "steadylight/run/memory_model.h"
#include "steadylight/run/settings_file.h"

namespace steadylight {
namespace {

/// True when something in the scene emits light: an emitting object, a point or spot light, a
/// sun or the world.
bool has_light(const SceneDesc& desc) {
    return std::any_of(desc.objects.begin(), desc.objects.end(), [](const ObjectDesc& o) { return o.is_emitter(); }) ||
           std::any_of(desc.point_lights.begin(), desc.point_lights.end(),
                       [](const PointLightDesc& light) {
                           return light.intensity_track ? is_ever_lit(*light.intensity_track)
                                                        : !is_black(light.intensity);
                       }) ||
           has_distant_light(desc);
}

/// True when a lamp, a sun or an emitting object moves (PhotonGroup::moving).
bool moves_a_light(const SceneDesc& desc) {
    return std::any_of(desc.point_lights.begin(), desc.point_lights.end(),
                       [](const PointLightDesc& light) { return light.is_moving(); }) ||
           std::any_of(desc.suns.begin(), desc.suns.end(), [](const SunLightDesc& sun) { return sun.is_moving(); }) ||
           std::any_of(desc.objects.begin(), desc.objects.end(),
                       [](const ObjectDesc& o) { return o.is_moving_light(); });
}

/// True when some light stands still: an emitter, a lamp or a sun that does not move, the world.
bool has_still_light(const SceneDesc& desc) {
    return std::any_of(desc.objects.begin(), desc.objects.end(),
                       [](const ObjectDesc& o) { return o.is_emitter() && !o.is_moving_light(); }) ||
           std::any_of(desc.point_lights.begin(), desc.point_lights.end(),
                       [](const PointLightDesc& light) { return !light.is_moving(); }) ||
           std::any_of(desc.suns.begin(), desc.suns.end(), [](const SunLightDesc& sun) { return !sun.is_moving(); }) ||
           desc.world.has_value();
}

Scene load_scene(const RenderSettings& settings) {
    Scene scene(load_scene_desc(settings.scene_file, settings.confine_inputs));
    const SceneDesc& desc = scene.desc();
    if (!has_light(desc))
        spdlog::warn(
            "{}: the scene has no light (no object with an emission, no point or spot light with an "
            "intensity, no sun, no world): every frame renders black",
            settings.scene_file);
    // Lights that move are lit apart from the static pass (docs/localized.md, "Lights that move").
    if (settings.method == Method::frozen && moves_a_light(desc))
        spdlog::warn("{}: lights move: the frozen baseline leaves out their indirect light", settings.scene_file);
    if (settings.method == Method::localized && moves_a_light(desc) && !has_still_light(desc))
        spdlog::info(
            "{}: every light moves, so the static pass holds no light and every frame gathers anew: the photon method "
            "(--method photon) renders this faster",
            settings.scene_file);
    scene.set_resolution(settings.width.value_or(desc.camera.width), settings.height.value_or(desc.camera.height));
    scene.set_transparent_background(settings.output.transparent_background);
    // Photons of light from far away aimed where the camera's view shows it comes in, unless
    // portals say (scene/distant_photon_targets.h).
    if (settings.method != Method::path)
        if (const std::optional<size_t> marked = aim_distant_photons(scene))
            spdlog::info("photons from far away aimed at {} cells where the camera's view shows light coming in",
                         *marked);
    return scene;
}

/// The segment pass of `segment`, from its cache file when that matches; it keeps `paths`.
StaticSolution static_pass(const RenderSettings& settings, const Scene& scene, RayTracer& tracer,
                           const Segment& segment, std::shared_ptr<const StaticPhotonPaths> paths = nullptr) {
    const std::string file = static_cache_file(settings.cache_file, settings.out_dir, scene, segment);
    return load_or_run_segment_pass(scene, tracer, segment, settings.photon, file,
                                    settings.require_cache ? CacheUse::require : CacheUse::load_or_compute,
                                    std::move(paths));
}

/// Before any work: a static cache file of a method that has one cannot be a folder (it would
/// fail only when the cache is computed and written).
void check_cache_files(const RenderSettings& settings, const Scene& scene) {
    if (!method_info(settings.method).has_static_pass) return;
    for (const Segment& segment : scene.segments()) {
        const std::string file = static_cache_file(settings.cache_file, settings.out_dir, scene, segment);
        if (std::filesystem::is_directory(file)) throw InputError("--cache-file", file + " is a folder, not a file");
    }
}

/// Whether frames compose their photon maps from static photon paths (photon_paths.h).
bool reuses_photon_paths(const RenderSettings& settings) {
    return settings.reuse && method_info(settings.method).reads.photon;
}

/// Whether the segment's static photon paths are traced: for frames to compose their maps from,
/// and for the frame pass (the localized and frozen methods) to carry the static irradiance
/// values from, its photons traced whole or not (ChangedValues::carried).
bool traces_static_photon_paths(const RenderSettings& settings) {
    return reuses_photon_paths(settings) || settings.method == Method::localized || settings.method == Method::frozen;
}

/// Whether frames compute their method's analysis layers: only when the files hold them.
AnalysisLayers analysis_layers(const RenderSettings& settings) {
    return settings.output.layers == LayerSet::all ? AnalysisLayers::made : AnalysisLayers::left_out;
}

/// What every frame of `segment` starts from: the method's static pass (or its file), and the
/// static photon paths when frames use them. Only for methods that have either.
StaticSolution segment_solution(const RenderSettings& settings, const Scene& scene, RayTracer& tracer,
                                const Segment& segment) {
    std::shared_ptr<const StaticPhotonPaths> paths;
    if (traces_static_photon_paths(settings)) {
        const Stopwatch time;
        paths = trace_segment_photon_paths(scene, tracer, segment, settings.photon);
        spdlog::info("static photon paths: {} global and {} caustic paths, {} rays, {:.1f} MB, traced in {:.2f} s",
                     paths->global.count, paths->caustic.count,
                     paths->global.segments.size() + paths->caustic.segments.size(), double(paths->bytes()) / 1e6,
                     time.elapsed_s());
    }
    if (!method_info(settings.method).has_static_pass)
        return {IrradianceCache(settings.photon.cache), 0, false, "", std::move(paths)};
    StaticSolution solution = static_pass(settings, scene, tracer, segment, std::move(paths));
    solution.compose_photons = reuses_photon_paths(settings);
    if (settings.reuse && settings.method == Method::localized && solution.photon_paths)
        solution.static_frame =
            segment_static_frame(scene, tracer, segment, solution, settings.photon, settings.localized,
                                 double(memory_available().bytes), analysis_layers(settings));
    return solution;
}

void write_frame(const RenderSettings& settings, const Scene& scene, int frame, const RenderedFrame& rendered) {
    const OutputSettings& output = settings.output;
    const Image* alpha = rendered.alpha ? &*rendered.alpha : nullptr;
    const std::string exr = frame_file_name(settings.out_dir, scene.name(), frame, "exr");
    if (output.blender_view_layer.empty()) {
        write_exr(exr, frame_exr_layers(rendered.beauty, rendered.layers, alpha), output.exr_type);
    } else {
        Image opaque(rendered.beauty.width, rendered.beauty.height);
        std::fill(opaque.pixels.begin(), opaque.pixels.end(), Rgb{1, 1, 1});
        write_exr(
            exr,
            blender_exr_layers(output.blender_view_layer, rendered.beauty, rendered.layers, alpha ? *alpha : opaque),
            output.exr_type);
    }
    write_png(frame_file_name(settings.out_dir, scene.name(), frame, "png"), rendered.beauty, output.view, alpha);
    if (settings.aov_pngs)
        for (const NamedImage& layer : rendered.layers) {
            const std::string png = frame_file_name(settings.out_dir, scene.name(), frame, layer.name + ".png");
            if (const GreyImage* grey = layer.grey())
                write_png(png, colour_of(*grey), output.view);
            else
                write_png(png, std::get<Image>(layer.image), output.view);
        }
    if (rendered.stats)
        write_text_file(frame_file_name(settings.out_dir, scene.name(), frame, "stats.json"),
                        nlohmann::json(*rendered.stats).dump(2) + "\n");
}

/// Encodes the PNGs of the selected frames into `--video` (check_video_possible has accepted
/// `frames`). Frames skipped as complete from an earlier run have their PNGs already.
void write_video(const RenderSettings& settings, const Scene& scene, const std::vector<int>& frames) {
    const auto [first, last] = *contiguous_span(frames);
    encode_video({.out_dir = settings.out_dir,
                  .scene_name = scene.name(),
                  .first_frame = first,
                  .frame_count = last - first + 1,
                  .fps = scene.desc().fps,
                  .output = settings.output.video_file,
                  .alpha = settings.output.transparent_background});
    spdlog::info("video: {} frames at {} fps written to {}", last - first + 1, scene.desc().fps,
                 settings.output.video_file);
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

/// Removes the claim that a process killed between claiming `frame` and finding it complete
/// left beside it, once its holder is dead (taken over, then released): no one else would, since
/// a complete frame is never claimed again.
void remove_dead_claim(const RenderSettings& settings, const Scene& scene, int frame) {
    if (!std::filesystem::exists(frame_claim_name(settings.out_dir, scene.name(), frame))) return;
    const LockAttempt attempt = try_claim_frame(settings.out_dir, scene.name(), frame);
    if (attempt.lock && !attempt.taken_over.empty())
        spdlog::info("frame {}: removed the dead claim left beside the complete frame ({})", frame, attempt.taken_over);
}

/// The selected frames whose outputs are not complete yet (all of them with --overwrite).
std::vector<int> frames_to_render(const RenderSettings& settings, const Scene& scene, const std::vector<int>& frames,
                                  const std::string& key, RenderSummary& summary) {
    if (settings.overwrite) return frames;
    std::vector<int> todo, complete;
    for (const int frame : frames) {
        const FrameCheck check = check_frame_outputs(settings.out_dir, scene.name(), frame, key);
        (check.complete ? complete : todo).push_back(frame);
        if (check.complete) remove_dead_claim(settings, scene, frame);
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

bool contains(const std::vector<int>& frames, int frame) {
    return std::find(frames.begin(), frames.end(), frame) != frames.end();
}

/// Drops the AOV layers that `chosen` (--layers) leaves out of the files; `info` is the method's.
void keep_chosen_layers(RenderedFrame& rendered, const MethodInfo& info, LayerSet chosen) {
    if (chosen == LayerSet::all) return;
    SL_CHECK(rendered.layers.size() == info.layers.size());
    std::vector<NamedImage> kept;
    for (size_t i = 0; i < info.layers.size(); ++i)
        if (chosen == LayerSet::terms && info.layers[i].kind == LayerKind::term)
            kept.push_back(std::move(rendered.layers[i]));
    rendered.layers = std::move(kept);
}

/// One frame: the scene placed there and the method's frame pass, with the layers --layers
/// chooses. A value that is not finite leaves as 0, counted in the frame's statistics and
/// reported (output/frame_layers.h).
RenderedFrame render_frame(const RenderSettings& settings, const Scene& scene, RayTracer& tracer, const Bsdfs& bsdfs,
                           const StaticSolution* solution, const CameraSeenSides* seen, int frame) {
    const PlacedFrame placed(scene, tracer, bsdfs, frame);
    const MethodInfo& info = method_info(settings.method);
    RenderedFrame rendered = info.render_frame(placed.context(), solution, settings, analysis_layers(settings));
    keep_chosen_layers(rendered, info, settings.output.layers);
    if (rendered.stats && seen)
        rendered.stats->distant_photons_inside = distant_photons_inside(placed.context(), *seen).value_or(-1);
    const NonFiniteValues non_finite = replace_non_finite(rendered.beauty, rendered.layers);
    if (non_finite.count > 0)
        spdlog::warn(
            "frame {}: {} channel value(s) were NaN or infinite and are written as 0, the first in layer {} "
            "at pixel ({}, {}): a defect, please report it with the scene",
            frame, non_finite.count, non_finite.first_layer, non_finite.first_x, non_finite.first_y);
    if (rendered.stats) rendered.stats->non_finite_values = non_finite.count;
    return rendered;
}

/// Writes a rendered frame on `writer`'s thread while the next one renders, holding the frame's
/// claim until its manifest is written; logs the frame's line when done.
void write_in_background(FrameWriter& writer, const RenderSettings& settings, const Scene& scene, int frame,
                         RenderedFrame rendered, std::unique_ptr<LockFile> claim, const std::string& key,
                         double render_s) {
    writer.write(frame, [&settings, &scene, frame, &key, render_s, rendered = std::move(rendered),
                         claim = std::move(claim)]() mutable {
        const Stopwatch time;
        write_frame_outputs(settings, scene, frame, rendered, key);
        const double write_s = time.elapsed_s();
        // Complete now: released here, not when the next frame's write replaces this one (a
        // process killed inside the next frame would leave this claim for ever, and processes
        // waiting for the frame would wait on it).
        claim.reset();
        spdlog::info("frame {:4d}  {:7.2f} s  {}  (written in {:.2f} s, beside the next frame){}", frame, render_s,
                     frame_file_name(settings.out_dir, scene.name(), frame, "exr"), write_s,
                     rendered.stats ? "  |  " + summarize(*rendered.stats) : "");
    });
}

/// This process's claim on `frame` (run/frame_claim.h), or nothing when another process holds
/// it (then `holder` says who) or has completed the frame meanwhile (noted in `summary`).
std::unique_ptr<LockFile> claim_frame(const RenderSettings& settings, const Scene& scene, int frame,
                                      const std::string& key, RenderSummary& summary, std::string& holder) {
    LockAttempt attempt = try_claim_frame(settings.out_dir, scene.name(), frame);
    holder = attempt.holder;
    if (!attempt.lock) return nullptr;
    if (!attempt.taken_over.empty()) spdlog::warn("frame {}: took over a dead claim ({})", frame, attempt.taken_over);
    if (!settings.overwrite && check_frame_outputs(settings.out_dir, scene.name(), frame, key).complete) {
        spdlog::info("frame {}: completed by another process meanwhile, skipped", frame);
        ++summary.frames_skipped;
        summary.frames_completed_elsewhere.push_back(frame);
        return nullptr;
    }
    return std::move(attempt.lock);
}

/// Waits for the frames that other processes claimed (in `summary`), looking once a second: a
/// frame its holder completed is done; one whose claim is dead (or released without the frame
/// complete) is claimed here and given to `render_claimed`. Stops at the first checkpoint after
/// Ctrl-C.
void wait_for_claimed_frames(const RenderSettings& settings, const Scene& scene, const std::string& key,
                             RenderSummary& summary,
                             const std::function<void(int, std::unique_ptr<LockFile>)>& render_claimed) {
    std::vector<int>& waiting = summary.frames_claimed_elsewhere;
    if (waiting.empty()) return;
    spdlog::info("waiting for frame(s) {}, claimed by other processes: each is taken over if its holder dies",
                 format_frame_list(waiting));
    const double poll_s = std::min(1.0, lock_times().refresh_s);
    while (!waiting.empty()) {
        for (const Stopwatch pause; pause.elapsed_s() < poll_s;) {
            throw_if_interrupted();
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
        for (const int frame : std::vector<int>(waiting)) {
            std::string holder;
            std::unique_ptr<LockFile> claim = claim_frame(settings, scene, frame, key, summary, holder);
            if (!holder.empty()) continue;
            std::erase(waiting, frame);
            if (claim) render_claimed(frame, std::move(claim));
        }
    }
}

/// Renders and writes `frames` (sorted) in order: for each segment its static pass (when the
/// method has one), then its frames, each under this process's claim. Frames that other
/// processes hold are waited for at the end: each is completed by its holder, or taken over and
/// rendered here when its holder dies. Adds each frame to `summary` when written; each frame is
/// written while the next renders (run/frame_writer.h). Throws RenderInterrupted at the first
/// checkpoint after Ctrl-C, after the frame before it is written.
void render_frames(const RenderSettings& settings, const Scene& scene, const std::vector<int>& frames,
                   const std::string& key, RenderSummary& summary) {
    if (frames.empty()) return;
    // Build the acceleration structures once; each frame only moves the dynamic objects.
    RayTracer tracer(scene, scene.evaluate(frames.front()));
    const Bsdfs bsdfs = make_bsdfs(scene);
    ConsoleProgress progress(int(frames.size()), settings.show_progress);
    const ScopedCheckpointListener listening(&progress);
    const std::optional<int> interrupt_after = test_interrupt_after_frames();
    FrameWriter writer([&summary](int frame) { summary.frames_written.push_back(frame); });
    const bool needs_solution = method_info(settings.method).has_static_pass || traces_static_photon_paths(settings);
    // Photon methods say how many photons of light from far away reach what the camera sees.
    const std::optional<CameraSeenSides> seen = settings.method != Method::path && has_distant_light(scene.desc())
                                                    ? std::optional<CameraSeenSides>(std::in_place, scene, tracer)
                                                    : std::nullopt;
    // The static pass of the segment whose frames render now: run (or loaded) with its first
    // frame rendered here, freed when the next segment's is made.
    std::optional<StaticSolution> solution;
    const Segment* solved = nullptr;
    int rendered_here = 0;
    const auto render_claimed = [&](int frame, std::unique_ptr<LockFile> claim) {
        const Segment& segment = scene.segment_of(frame);
        if (needs_solution && solved != &segment) {
            solution.reset();
            solution = segment_solution(settings, scene, tracer, segment);
            solved = &segment;
        }
        if (interrupt_after == rendered_here) std::raise(SIGINT);
        const Stopwatch time;
        RenderedFrame rendered = render_frame(settings, scene, tracer, bsdfs, solution ? &*solution : nullptr,
                                              seen ? &*seen : nullptr, frame);
        write_in_background(writer, settings, scene, frame, std::move(rendered), std::move(claim), key,
                            time.elapsed_s());
        ++rendered_here;
    };
    try {
        for (const int frame : frames) {
            progress.begin_frame(frame);
            std::string holder;
            if (std::unique_ptr<LockFile> claim = claim_frame(settings, scene, frame, key, summary, holder)) {
                render_claimed(frame, std::move(claim));
            } else if (!holder.empty()) {
                spdlog::info("frame {}: claimed by another process ({}), left to it for now", frame, holder);
                summary.frames_claimed_elsewhere.push_back(frame);
            }
            progress.finish_frame();
        }
        wait_for_claimed_frames(settings, scene, key, summary, render_claimed);
        writer.finish();
    } catch (...) {
        writer.finish_quietly();  // a frame rendered before Ctrl-C is still written whole
        throw;
    }
}

/// The frames of `todo` that are neither written by this run nor left to or finished by others.
std::vector<int> frames_left(const std::vector<int>& todo, const RenderSummary& summary) {
    std::vector<int> left;
    for (const int frame : todo)
        if (!contains(summary.frames_written, frame) && !contains(summary.frames_claimed_elsewhere, frame) &&
            !contains(summary.frames_completed_elsewhere, frame))
            left.push_back(frame);
    return left;
}

/// `--check-complete`: an InputError listing the selected frames in `todo` (not complete).
void check_complete(const RenderSettings& settings, const std::vector<int>& frames, const std::vector<int>& todo) {
    if (!todo.empty())
        throw InputError(settings.out_dir, fmt::format("{} of the {} selected frame(s) are not complete: {}",
                                                       todo.size(), frames.size(), format_frame_list(todo)));
    spdlog::info("all {} selected frame(s) are complete", frames.size());
}

/// ": 0-9, 10-19" for a few segments; nothing for one or for many.
std::string segment_list(const std::vector<Segment>& segments) {
    constexpr size_t max_listed = 8;
    if (segments.size() < 2 || segments.size() > max_listed) return "";
    std::string text;
    for (const Segment& segment : segments)
        text += fmt::format("{} {}-{}", text.empty() ? ":" : ",", segment.first, segment.last);
    return text;
}

}  // namespace

RenderSummary render_animation(const RenderSettings& settings) {
    const Stopwatch time;
    validate(settings);
    const Scene scene = load_scene(settings);
    const std::vector<int> frames = select_frames(settings.frames, scene.frame_count());
    if (!settings.output.video_file.empty()) check_video_possible(frames);  // before hours of rendering
    check_memory(estimate_memory(settings, scene), memory_available());
    create_output_folder(settings.out_dir, "--out");
    check_cache_files(settings, scene);
    const std::string key = record_settings(settings, scene, frames);
    RenderSummary summary;
    const std::vector<int> todo = frames_to_render(settings, scene, frames, key, summary);
    if (settings.check_complete) check_complete(settings, frames, todo);
    try {
        if (!settings.check_complete) render_frames(settings, scene, todo, key, summary);
    } catch (const RenderInterrupted&) {
        summary.interrupted = true;
    }
    summary.frames_left = frames_left(todo, summary);
    // The video needs every selected frame: after an interrupt, the resumed run makes it. (Frames
    // other processes claimed were waited for.)
    if (!settings.output.video_file.empty() && !summary.interrupted) write_video(settings, scene, frames);
    summary.seconds = time.elapsed_s();
    return summary;
}

std::vector<std::string> bake_static_caches(const RenderSettings& settings, std::optional<int> only_segment) {
    validate(settings);
    const Scene scene = load_scene(settings);
    const std::vector<Segment>& segments = scene.segments();
    if (only_segment && (*only_segment < 0 || *only_segment >= int(segments.size())))
        throw InputError("--segment",
                         fmt::format("{} is not a segment of {}: it has {} (0 to {}; see steadylight info)",
                                     *only_segment, settings.scene_file, segments.size(), segments.size() - 1));
    check_memory(estimate_memory(settings, scene), memory_available());
    create_output_folder(settings.out_dir, "--out");
    check_cache_files(settings, scene);
    RayTracer tracer(scene, scene.evaluate(only_segment ? segments[size_t(*only_segment)].first : 0));
    std::vector<std::string> files;
    for (const Segment& segment : segments) {
        if (only_segment && segment.first != segments[size_t(*only_segment)].first) continue;
        static_pass(settings, scene, tracer, segment);
        files.push_back(static_cache_file(settings.cache_file, settings.out_dir, scene, segment));
    }
    return files;
}

std::string describe_scene(const std::string& scene_file, bool confine_inputs) {
    const Scene scene(load_scene_desc(scene_file, confine_inputs));
    const SceneDesc& desc = scene.desc();
    std::string text = fmt::format("scene {} ({})\n", desc.name, scene_file);
    text += fmt::format("frames: {} at {:.6g} fps ({}) ({:.2f} s), {} segment(s){}\n", desc.frame_count, desc.fps,
                        describe_fps_source(desc), desc.frame_count / desc.fps, scene.segments().size(),
                        segment_list(scene.segments()));
    text += fmt::format("camera: {}x{}, vertical fov {} deg{}\n", desc.camera.width, desc.camera.height,
                        desc.camera.fov_y_deg, is_chain_animated(desc.camera.placement) ? ", animated" : "");
    int area_lights = 0, animated_lights = 0;
    std::string objects;
    for (size_t i = 0; i < desc.objects.size(); ++i) {
        const ObjectDesc& object = desc.objects[i];
        const auto* mesh = std::get_if<TriangleMesh>(&object.geometry);
        const long count = mesh ? long(mesh->indices.size() / 3) : 0;
        area_lights += object.is_emitter();
        animated_lights += object.is_emitter() && (object.is_emission_animated() || object.is_dynamic());
        const char* emitter = object.is_emission_animated() ? "emitter, animated emission"
                              : object.is_emitter()         ? "emitter"
                                                            : "";
        objects +=
            fmt::format("  {:<20} {:<8} {:>8} {:<10} {}{}\n", object.name, object.is_dynamic() ? "dynamic" : "static",
                        mesh ? fmt::format("{} tris", count) : "sphere", desc.materials[size_t(object.material)].name,
                        emitter, object.marked_dynamic && !is_chain_animated(object.placement) ? " (marked)" : "");
    }
    for (const PointLightDesc& light : desc.point_lights)
        animated_lights += light.is_intensity_animated() || light.is_moving();
    for (const SunLightDesc& sun : desc.suns) animated_lights += sun.is_moving();
    text += fmt::format("objects: {} ({} static, {} dynamic), {} triangles\n", desc.objects.size(),
                        scene.static_objects().size(), scene.dynamic_objects().size(), triangle_count(desc));
    text += objects;
    text +=
        fmt::format("lights: {} area, {} point/spot, {} sun", area_lights, desc.point_lights.size(), desc.suns.size());
    text +=
        animated_lights
            ? fmt::format(", {} animated (switched, dimmed or moved; a new segment where one is switched or dimmed)\n",
                          animated_lights)
            : std::string("\n");
    const FrameState first = scene.evaluate(0);
    for (size_t i = 0; i < desc.point_lights.size(); ++i) {
        const PointLightDesc& light = desc.point_lights[i];
        const Vec3 p = first.point_lights[i].position;
        text += fmt::format("  {:<20} {}{}{}, at ({:.3g}, {:.3g}, {:.3g}){}\n", light.name,
                            light.type == PointLightType::point ? "point" : "spot",
                            light.is_moving() ? ", moves" : ", still",
                            light.is_intensity_animated() ? ", animated intensity" : "", p.x, p.y, p.z,
                            light.is_moving() ? " at frame 0" : "");
    }
    for (size_t i = 0; i < desc.suns.size(); ++i) {
        const SunLightDesc& sun = desc.suns[i];
        const Vec3 d = first.sun_directions[i];
        text += fmt::format("  {:<20} sun{}, travelling ({:.3f}, {:.3f}, {:.3f}){}, {:.3g} W/m² (luminance), {:.2f}°\n",
                            sun.name, sun.is_moving() ? ", moves" : ", still", d.x, d.y, d.z,
                            sun.is_moving() ? " at frame 0" : "", luminance(sun.irradiance), sun.angle_deg);
    }
    if (desc.world) {
        text += fmt::format("world: {}\n", desc.world->description);
    } else {
        text += "world: none (the background is black)\n";
    }
    for (const PortalDesc& portal : desc.portals)
        text += fmt::format("portal: corner ({:.3g}, {:.3g}, {:.3g}), {:.3g} m², facing ({:.3f}, {:.3f}, {:.3f})\n",
                            portal.corner.x, portal.corner.y, portal.corner.z, portal.area(), portal.inward_normal().x,
                            portal.inward_normal().y, portal.inward_normal().z);
    text += fmt::format("materials: {}\n", desc.materials.size());
    return text;
}

}  // namespace steadylight
