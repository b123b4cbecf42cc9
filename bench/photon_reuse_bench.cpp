// Photon paths reused (photons/photon_paths.h) against photons traced whole, side by side in
// one run on BALL and TABLE. Per frame: the frame's photon phase as the photon and localized
// methods both run it (FramePhotons: the global, caustic and dynamic maps and the index of the
// irradiance photons), with and without reuse, the photon paths traced, and a bit-for-bit check
// that both give the same maps. With --method-frames N, also N whole frames of the photon and
// localized methods with and without reuse: their photon-phase and frame times, and whether the
// images are identical. Prints, asserts nothing.
// Run: build/photon_reuse_bench [--scenes ball,table] [--frames N] [--size WxH] [--method-frames N]
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>

#include "scene_bench_options.h"
#include "steadylight/base/freed_memory.h"
#include "steadylight/base/stopwatch.h"
#include "steadylight/methods/photon_mapping.h"
#include "steadylight/passes/frame_pass.h"
#include "steadylight/passes/frame_photons.h"

using namespace steadylight;

namespace {

using Options = SceneBenchOptions;

/// One frame's photon phase: its time (the phase, and with the irradiance photons' index) and counts.
struct PhotonPhase {
    double phase_s = 0, with_index_s = 0;
    long traced_paths = 0, dynamic_photons = 0;
};

struct TimedPhotons {
    std::unique_ptr<FramePhotons> photons;
    PhotonPhase phase;
};

TimedPhotons time_photon_phase(const FrameContext& context, const PhotonMappingSettings& settings,
                               const StaticPhotonPaths* paths) {
    FrameStats stats;
    const Stopwatch time;
    auto photons = std::make_unique<FramePhotons>(context, settings, stats, paths);
    const double seconds = time.elapsed_s();
    return {std::move(photons),
            {stats.photon_tracing_s, seconds, stats.retraced_photon_paths, stats.dynamic_photons_stored}};
}

bool same_maps(const FramePhotons& a, const FramePhotons& b) {
    return same_photons(a.maps.global, b.maps.global) && same_photons(a.maps.caustic, b.maps.caustic) &&
           same_photons(a.maps.dynamic, b.maps.dynamic);
}

/// Every frame's photon phase with and without reuse, in alternating order (the machine is shared).
void compare_photon_phases(const Scene& scene, RayTracer& tracer, const Bsdfs& bsdfs, const StaticPhotonPaths& paths,
                           const PhotonMappingSettings& settings, int frames) {
    std::printf("%5s %12s %12s %12s %12s %10s %9s %10s %6s\n", "frame", "whole s", "reuse s", "whole+idx s",
                "reuse+idx s", "paths", "of", "dyn.phot.", "same");
    PhotonPhase whole_sum, reuse_sum;
    int same = 0;
    for (int f = 0; f < frames; ++f) {
        const PlacedFrame placed(scene, tracer, bsdfs, f);
        TimedPhotons whole_run, reuse_run;
        if (f % 2) reuse_run = time_photon_phase(placed.context(), settings, &paths);
        whole_run = time_photon_phase(placed.context(), settings, nullptr);
        if (!(f % 2)) reuse_run = time_photon_phase(placed.context(), settings, &paths);
        const PhotonPhase &whole = whole_run.phase, &reuse = reuse_run.phase;
        const bool equal = same_maps(*whole_run.photons, *reuse_run.photons);
        same += equal;
        std::printf("%5d %12.4f %12.4f %12.4f %12.4f %10ld %9ld %10ld %6s\n", f, whole.phase_s, reuse.phase_s,
                    whole.with_index_s, reuse.with_index_s, reuse.traced_paths, whole.traced_paths,
                    reuse.dynamic_photons, equal ? "yes" : "NO");
        whole_sum.phase_s += whole.phase_s, whole_sum.with_index_s += whole.with_index_s;
        reuse_sum.phase_s += reuse.phase_s, reuse_sum.with_index_s += reuse.with_index_s;
        reuse_sum.traced_paths += reuse.traced_paths, whole_sum.traced_paths += whole.traced_paths;
    }
    std::printf("%5s %12.4f %12.4f %12.4f %12.4f %10.0f %9.0f   (means; maps identical in %d of %d frames)\n", "mean",
                whole_sum.phase_s / frames, reuse_sum.phase_s / frames, whole_sum.with_index_s / frames,
                reuse_sum.with_index_s / frames, double(reuse_sum.traced_paths) / frames,
                double(whole_sum.traced_paths) / frames, same, frames);
    std::printf("photon phase, whole / reuse: %.1fx (with the irradiance photons' index %.1fx)\n",
                whole_sum.phase_s / reuse_sum.phase_s, whole_sum.with_index_s / reuse_sum.with_index_s);
}

/// The look-ups of the irradiance photons (k = 64 at every 4th global photon) through the
/// composed map's two trees and through one tree built over the whole map: time and agreement.
void compare_look_ups(const Scene& scene, RayTracer& tracer, const Bsdfs& bsdfs, const StaticPhotonPaths& paths,
                      int frame) {
    const PlacedFrame placed(scene, tracer, bsdfs, frame);
    const PhotonMap composed = compose_photons(placed.context(), paths).maps.global;
    const Stopwatch build_time;
    const PhotonMap rebuilt(composed.photons(), composed.emitted());
    const double build_s = build_time.elapsed_s();
    const auto time_look_ups = [&](const PhotonMap& map, double& sum) {
        const Stopwatch time;
        std::vector<Neighbour> found;
        for (size_t i = 0; i < map.size(); i += 4) {
            map.k_nearest(map.photons()[i].p, 64, 0.5f, found);
            for (const Neighbour& n : found) sum += n.distance2;
        }
        return time.elapsed_s();
    };
    // The fastest of three runs each, alternating (the machine is shared).
    double sum_rebuilt = 0, sum_composed = 0, rebuilt_s = 1e30, composed_s = 1e30;
    for (int run = 0; run < 3; ++run) {
        rebuilt_s = std::min(rebuilt_s, time_look_ups(rebuilt, sum_rebuilt));
        composed_s = std::min(composed_s, time_look_ups(composed, sum_composed));
    }
    std::printf(
        "frame %d look-ups (k 64 at every 4th of %zu photons, 1 thread, best of 3): rebuilt tree %.3f s (built in %.3f "
        "s), "
        "composed %.3f s (%zu photons in its own tree), %s\n",
        frame, composed.size(), rebuilt_s, build_s, composed_s, composed.indexed_here(),
        sum_rebuilt == sum_composed ? "same distances" : "DIFFERENT");
}

bool same_image(const Image& a, const Image& b) {
    return a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Rgb)) == 0;
}

/// Whole frames of the photon and localized methods, with and without reuse.
void compare_methods(const Scene& scene, RayTracer& tracer, const Bsdfs& bsdfs,
                     std::shared_ptr<const StaticPhotonPaths> paths, const PhotonMappingSettings& settings, int count) {
    const Stopwatch static_time;
    StaticSolution solution{run_segment_pass(scene, tracer, {0, scene.frame_count() - 1}, settings)};
    std::printf("static cache %.2f s\n%5s %-10s %12s %12s %12s %12s %6s\n", static_time.elapsed_s(), "frame", "method",
                "photons s", "reuse", "frame s", "reuse", "same");
    const LocalizedSettings localized;
    for (int i = 0; i < count; ++i) {
        const int f = i * scene.frame_count() / count;
        const PlacedFrame placed(scene, tracer, bsdfs, f);
        const PhotonFrame a = render_photon_mapped(placed.context(), settings);
        const PhotonFrame b = render_photon_mapped(placed.context(), settings, paths.get());
        std::printf("%5d %-10s %12.4f %12.4f %12.3f %12.3f %6s\n", f, "photon", a.stats.photon_tracing_s,
                    b.stats.photon_tracing_s, a.stats.total_s, b.stats.total_s,
                    same_image(a.beauty, b.beauty) ? "yes" : "NO");
        solution.photon_paths = nullptr;
        const LocalizedFrame c =
            run_frame_pass(placed.context(), solution, settings, localized, StaticCacheUse::corrected);
        solution.photon_paths = paths;
        const LocalizedFrame d =
            run_frame_pass(placed.context(), solution, settings, localized, StaticCacheUse::corrected);
        std::printf("%5d %-10s %12.4f %12.4f %12.3f %12.3f %6s\n", f, "localized", c.stats.photon_tracing_s,
                    d.stats.photon_tracing_s, c.stats.total_s, d.stats.total_s,
                    same_image(c.beauty, d.beauty) ? "yes" : "NO");
    }
}

void run_scene(const std::string& name, const Options& options) {
    BenchScene opened(name, options);
    auto& [scene, tracer, bsdfs] = opened;
    const PhotonMappingSettings settings;
    const Stopwatch static_time;
    const auto paths = trace_segment_photon_paths(scene, tracer, {0, scene.frame_count() - 1}, settings);
    std::printf("\n%s: static photon paths %.3f s: %ld global + %ld caustic paths, %zu rays, %.1f MB\n", name.c_str(),
                static_time.elapsed_s(), paths->global.count, paths->caustic.count,
                paths->global.segments.size() + paths->caustic.segments.size(), double(paths->bytes()) / 1e6);
    compare_photon_phases(scene, tracer, bsdfs, *paths, settings, std::min(options.frames, scene.frame_count()));
    compare_look_ups(scene, tracer, bsdfs, *paths, scene.frame_count() / 2);
    if (const int method_frames = options.number("method-frames", 0); method_frames > 0)
        compare_methods(scene, tracer, bsdfs, paths, settings, method_frames);
}

}  // namespace

int main(int argc, char** argv) {
    steadylight::keep_freed_memory_mapped();  // frames reuse their large arrays (freed_memory.h)
    const Options options = parse_scene_bench_options(argc, argv, 1000);
    for (const std::string& scene : options.scenes) run_scene(scene, options);
    return 0;
}
