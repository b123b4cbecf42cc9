// The paper's comparison (its Tables 1-3) on BALL and TABLE: every frame rendered with the
// photon method (from scratch), the frozen cache and the localized method, side by side:
// irradiance records computed per frame, time for photon tracing, influence, L_y and L_t, and
// the relative RMSE per pixel of frozen and localized against the photon method (the truth
// suite's figure, quality/image_error.h). Prints, asserts nothing. Error against converged
// references and temporal noise (which replaced the flicker figure this benchmark printed,
// since that counted moving shadows as flicker) are bench/quality_bench's.
// Run: build/animation_bench [--scenes ball,table] [--frames N] [--size WxH]
#include <cmath>
#include <cstdio>
#include <map>

#include "scene_bench_options.h"
#include "steadylight/base/freed_memory.h"
#include "steadylight/base/stopwatch.h"
#include "steadylight/methods/photon_mapping.h"
#include "steadylight/passes/frame_pass.h"
#include "steadylight/quality/image_error.h"

using namespace steadylight;

namespace {

using Options = SceneBenchOptions;

/// One method's figures summed over the frames.
struct Totals {
    double records = 0, photon_s = 0, influence_s = 0, L_y_s = 0, L_t_s = 0, total_s = 0;
    double rmse_vs_photon = 0;

    void add(const FrameStats& s) {
        records += double(s.irradiance_records);
        photon_s += s.photon_tracing_s, influence_s += s.influence_s, L_y_s += s.cache_s, L_t_s += s.correction_s;
        total_s += s.total_s;
    }
};

void run_scene(const std::string& name, const Options& options) {
    BenchScene opened(name, options);
    auto& [scene, tracer, bsdfs] = opened;
    const int frames = std::min(options.frames, scene.frame_count());
    const PhotonMappingSettings photon_settings;
    const LocalizedSettings localized;

    const Stopwatch static_time;
    const StaticSolution solution{run_segment_pass(scene, tracer, {0, scene.frame_count() - 1}, photon_settings)};
    const double static_s = static_time.elapsed_s();
    std::map<std::string, Totals> totals;
    for (int f = 0; f < frames; ++f) {
        const PlacedFrame placed(scene, tracer, bsdfs, f);
        const FrameContext& context = placed.context();
        const PhotonFrame photon = render_photon_mapped(context, photon_settings);
        const LocalizedFrame local =
            run_frame_pass(context, solution, photon_settings, localized, StaticCacheUse::corrected);
        const LocalizedFrame freeze =
            run_frame_pass(context, solution, photon_settings, localized, StaticCacheUse::frozen);
        totals["photon"].add(photon.stats);
        totals["localized"].add(local.stats);
        totals["frozen"].add(freeze.stats);
        const PixelMask emitters = emitter_mask(context);
        totals["localized"].rmse_vs_photon += image_error(local.beauty, photon.beauty, emitters).pixel_rmse;
        totals["frozen"].rmse_vs_photon += image_error(freeze.beauty, photon.beauty, emitters).pixel_rmse;
        std::fprintf(stderr, "\r%s: frame %d/%d", name.c_str(), f + 1, frames);
    }
    std::fprintf(stderr, "\n");

    std::printf("\n%s, %dx%d, %d frames; static pass %.2f s (%ld records)\n", name.c_str(), options.width,
                options.height, frames, static_s, solution.records());
    std::printf("per frame (means)        %12s %12s %12s   photon/localized\n", "photon", "frozen", "localized");
    const auto row = [&](const char* label, auto get) {
        const double p = get(totals["photon"]) / frames, z = get(totals["frozen"]) / frames,
                     l = get(totals["localized"]) / frames;
        std::printf("%-24s %12.3f %12.3f %12.3f   %8.1fx\n", label, p, z, l, l > 0 ? p / l : 0.0);
    };
    row("records (Table 1)", [](const Totals& t) { return t.records; });
    row("photon tracing s", [](const Totals& t) { return t.photon_s; });
    row("influence I s", [](const Totals& t) { return t.influence_s; });
    row("L_y (cache) s", [](const Totals& t) { return t.L_y_s; });
    row("L_t s", [](const Totals& t) { return t.L_t_s; });
    row("indirect total s", [](const Totals& t) { return t.influence_s + t.L_y_s + t.L_t_s; });
    row("frame total s", [](const Totals& t) { return t.total_s; });
    row("rel. RMSE vs photon", [](const Totals& t) { return t.rmse_vs_photon; });
    std::printf("%-24s %12.2f s (static pass + frames)\n", "localized animation",
                static_s + totals["localized"].total_s);
}

}  // namespace

int main(int argc, char** argv) {
    steadylight::keep_freed_memory_mapped();  // frames reuse their large arrays (freed_memory.h)
    const Options options = parse_scene_bench_options(argc, argv, 60);
    for (const std::string& scene : options.scenes) run_scene(scene, options);
    return 0;
}
