// The paper's comparison (its Tables 1-3) on BALL and TABLE: every frame rendered with the
// photon method (from scratch), the frozen cache and the localized method, side by side:
// irradiance records computed per frame, time for photon tracing, influence, L_y and L_t, the
// relative RMSE of frozen and localized against the photon method, and temporal flicker (mean
// absolute frame-to-frame change of luminance over the pixels no dynamic object ever covers,
// relative to their mean luminance), split into the change of the direct light (the same in
// every method: moving shadows) and of the indirect light. Prints, asserts nothing.
// With `--reference 1` it also renders the photon method at 5x the photons and 4x the gather
// rays, as a stand-in for the converged animation, and reports each method's temporal noise:
// the frame-to-frame change of (method - reference), which leaves out the real change of the
// lighting that the flicker figure counts.
// Run: build/animation_bench [--scenes ball,table] [--frames N] [--size WxH] [--reference 1]
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>

#include "steadylight/base/stopwatch.h"
#include "steadylight/methods/photon_mapping.h"
#include "steadylight/passes/frame_pass.h"

using namespace steadylight;

namespace {

struct Options {
    std::vector<std::string> scenes{"ball", "table"};
    int frames = 60;
    int width = 320, height = 240;
    bool reference = false;
};

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--frames")) o.frames = std::atoi(argv[i + 1]);
        if (!std::strcmp(argv[i], "--size")) std::sscanf(argv[i + 1], "%dx%d", &o.width, &o.height);
        if (!std::strcmp(argv[i], "--reference")) o.reference = std::atoi(argv[i + 1]) != 0;
        if (!std::strcmp(argv[i], "--scenes")) {
            o.scenes.clear();
            std::stringstream list(argv[i + 1]);
            for (std::string name; std::getline(list, name, ',');) o.scenes.push_back(name);
        }
    }
    return o;
}

/// One method's figures summed over the frames.
struct Totals {
    double records = 0, photon_s = 0, influence_s = 0, L_y_s = 0, L_t_s = 0, total_s = 0;
    double rmse_vs_photon = 0, flicker = 0, indirect_flicker = 0;
    std::vector<Image> images, indirect;  // beauty, and indirect + caustic light

    void add(const FrameStats& s) {
        records += double(s.irradiance_records);
        photon_s += s.photon_tracing_s, influence_s += s.influence_s, L_y_s += s.cache_s, L_t_s += s.correction_s;
        total_s += s.total_s;
    }
};

/// Pixels whose centre sees a dynamic object in some frame.
std::vector<bool> dynamic_coverage(const Scene& scene, RayTracer& tracer, int frames) {
    std::vector<bool> covered;
    for (int f = 0; f < frames; ++f) {
        const FrameState state = scene.evaluate(f);
        tracer.set_frame(state);
        covered.resize(size_t(state.camera.width * state.camera.height), false);
        for (int y = 0; y < state.camera.height; ++y)
            for (int x = 0; x < state.camera.width; ++x) {
                const std::optional<Hit> hit = tracer.intersect(state.camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f));
                if (hit && scene.object(hit->object).is_dynamic()) covered[size_t(y * state.camera.width + x)] = true;
            }
    }
    return covered;
}

double relative_rmse(const Image& a, const Image& b) {
    double sum2 = 0, sum = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        const double ya = std::min(1.0f, luminance(a.pixels[i])), yb = std::min(1.0f, luminance(b.pixels[i]));
        sum2 += (ya - yb) * (ya - yb), sum += yb;
    }
    return std::sqrt(sum2 / double(a.pixels.size())) / (sum / double(a.pixels.size()));
}

/// Display-referred luminance, as the PNG shows it (unclamped, the light's pixels would dominate).
double shown_luminance(Rgb c) { return std::min(1.0f, luminance(c)); }

/// Mean absolute frame-to-frame change of luminance of `layers` over the pixels no dynamic
/// object ever covers, relative to the mean shown luminance of `images` there. With layers =
/// images this is the flicker of the picture; with a layer (direct, indirect) it is that part's
/// share of it.
double flicker(const std::vector<Image>& layers, const std::vector<Image>& images, const std::vector<bool>& covered,
               bool shown) {
    double change = 0, level = 0;
    for (size_t f = 1; f < images.size(); ++f)
        for (size_t i = 0; i < covered.size(); ++i) {
            if (covered[i]) continue;
            const auto value = [&](const Image& image) {
                return shown ? shown_luminance(image.pixels[i]) : double(luminance(image.pixels[i]));
            };
            change += std::abs(value(layers[f]) - value(layers[f - 1])), level += shown_luminance(images[f].pixels[i]);
        }
    return level > 0 ? change / level : 0;
}

/// Mean absolute frame-to-frame change of (shown luminance of `images` - that of `reference`)
/// over the never-covered pixels, relative to the reference's mean shown luminance there.
double temporal_noise(const std::vector<Image>& images, const std::vector<Image>& reference, const std::vector<bool>& covered) {
    double change = 0, level = 0;
    for (size_t f = 1; f < images.size(); ++f)
        for (size_t i = 0; i < covered.size(); ++i) {
            if (covered[i]) continue;
            const auto error = [&](size_t frame) {
                return shown_luminance(images[frame].pixels[i]) - shown_luminance(reference[frame].pixels[i]);
            };
            change += std::abs(error(f) - error(f - 1)), level += shown_luminance(reference[f].pixels[i]);
        }
    return level > 0 ? change / level : 0;
}

Image sum(const Image& a, const Image& b) {
    Image out = a;
    for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] += b.pixels[i];
    return out;
}

void run_scene(const std::string& name, const Options& options) {
    Scene scene(load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/" + name + ".json"));
    scene.set_resolution(options.width, options.height);
    const int frames = std::min(options.frames, scene.frame_count());
    RayTracer tracer(scene, scene.evaluate(0));
    const Bsdfs bsdfs = make_bsdfs(scene);
    const PhotonMappingSettings photon_settings;
    const LocalizedSettings localized;

    const Stopwatch static_time;
    const StaticSolution solution{run_segment_pass(scene, tracer, {0, scene.frame_count() - 1}, photon_settings)};
    const double static_s = static_time.elapsed_s();
    std::map<std::string, Totals> totals;
    std::vector<Image> direct;     // the same in every method
    std::vector<Image> reference;  // --reference: the photon method with 5x photons, 4x gather rays
    PhotonMappingSettings reference_settings = photon_settings;
    reference_settings.photons.global_photons *= 5;
    reference_settings.photons.caustic_photons *= 5;
    reference_settings.gather.theta_strata *= 2, reference_settings.gather.phi_strata *= 2;
    for (int f = 0; f < frames; ++f) {
        const PlacedFrame placed(scene, tracer, bsdfs, f);
        const FrameContext& context = placed.context();
        PhotonFrame photon = render_photon_mapped(context, photon_settings);
        LocalizedFrame local = run_frame_pass(context, solution, photon_settings, localized, StaticCacheUse::corrected);
        LocalizedFrame freeze = run_frame_pass(context, solution, photon_settings, localized, StaticCacheUse::frozen);
        totals["photon"].add(photon.stats);
        totals["localized"].add(local.stats);
        totals["frozen"].add(freeze.stats);
        totals["localized"].rmse_vs_photon += relative_rmse(local.beauty, photon.beauty);
        totals["frozen"].rmse_vs_photon += relative_rmse(freeze.beauty, photon.beauty);
        if (options.reference) reference.push_back(render_photon_mapped(context, reference_settings).beauty);
        direct.push_back(std::move(photon.direct));
        totals["photon"].indirect.push_back(sum(photon.indirect, photon.caustic));
        totals["localized"].indirect.push_back(sum(local.indirect, local.caustic));
        totals["frozen"].indirect.push_back(sum(freeze.indirect, freeze.caustic));
        totals["photon"].images.push_back(std::move(photon.beauty));
        totals["localized"].images.push_back(std::move(local.beauty));
        totals["frozen"].images.push_back(std::move(freeze.beauty));
        std::fprintf(stderr, "\r%s: frame %d/%d", name.c_str(), f + 1, frames);
    }
    std::fprintf(stderr, "\n");
    const std::vector<bool> covered = dynamic_coverage(scene, tracer, frames);
    for (auto& [method, t] : totals) {
        t.flicker = flicker(t.images, t.images, covered, true);
        t.indirect_flicker = flicker(t.indirect, t.images, covered, false);
    }
    const double direct_flicker = flicker(direct, totals["photon"].images, covered, false);

    std::printf("\n%s, %dx%d, %d frames; static pass %.2f s (%ld records)\n", name.c_str(), options.width, options.height,
                frames, static_s, solution.records());
    std::printf("per frame (means)        %12s %12s %12s   photon/localized\n", "photon", "frozen", "localized");
    const auto row = [&](const char* label, auto get) {
        const double p = get(totals["photon"]) / frames, z = get(totals["frozen"]) / frames, l = get(totals["localized"]) / frames;
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
    std::printf("%-24s %12.5f %12.5f %12.5f   (mean |dY| / mean Y over never-covered pixels)\n", "flicker",
                totals["photon"].flicker, totals["frozen"].flicker, totals["localized"].flicker);
    std::printf("%-24s %12.5f %12.5f %12.5f   (indirect + caustic layers' change, same scale)\n", "  of it indirect",
                totals["photon"].indirect_flicker, totals["frozen"].indirect_flicker, totals["localized"].indirect_flicker);
    std::printf("%-24s %12.5f %12.5f %12.5f   (direct layer's change: the same in every method)\n", "  of it direct",
                direct_flicker, direct_flicker, direct_flicker);
    if (options.reference)
        std::printf("%-24s %12.5f %12.5f %12.5f   (change of the difference from a 5x-photon, 4x-gather photon render)\n",
                    "temporal noise", temporal_noise(totals["photon"].images, reference, covered),
                    temporal_noise(totals["frozen"].images, reference, covered),
                    temporal_noise(totals["localized"].images, reference, covered));
    std::printf("%-24s %12.2f s (static pass + frames)\n", "localized animation",
                static_s + totals["localized"].total_s);
}

}  // namespace

int main(int argc, char** argv) {
    const Options options = parse(argc, argv);
    for (const std::string& scene : options.scenes) run_scene(scene, options);
    return 0;
}
