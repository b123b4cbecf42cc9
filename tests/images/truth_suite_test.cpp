// The truth suite in CI: every suite scene, rendered small by every method, against its
// converged path-traced reference (tests/scenes/golden/, scripts/make_golden.sh: 80x60, 4096
// samples per pixel), with the suite's error figure (quality/image_error.h). The full-size
// references and figures are bench/quality_bench's. A frame that fails leaves its picture, the
// reference and their difference under the build folder (support/failure_pictures.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "steadylight/methods/method.h"
#include "steadylight/output/frame_layers.h"
#include "steadylight/output/image_writer.h"
#include "steadylight/passes/segment_pass.h"
#include "steadylight/photons/distant_photon_share.h"
#include "steadylight/quality/image_error.h"
#include "support/failure_pictures.h"

namespace steadylight {
namespace {

const std::string source_dir = STEADYLIGHT_SOURCE_DIR;

/// A suite scene and how close its 80x60 frame (0, or one in a later segment) must come to the reference with the
/// photon methods (16 camera rays per pixel). The per-pixel figure is mostly their noise: measured about 4% on the
/// diffuse scenes and TABLE (9% before caustic photons were aimed and sharp caustics averaged over the pixel), 8% with
/// the corridor's small lights (direct light noise), 7% with a moving glass ball (18% before) and 9.2-9.5% with a
/// glossy floor that sees a mirror (14% while the light's image in the mirror was left to the floor's sampled bounces,
/// 18% while they were one, not four); 4x4 blocks show bias (0.9-1.6% on the diffuse scenes and TABLE since the density
/// estimate was corrected, 2.2-4.6% on the noisy ones). The tolerances are those figures with a margin.
/// The path tracer (64 samples) gets 2.5 times the per-pixel figure, mirror_room's its own (34% measured: its glossy
/// floor's noise).
struct SceneTolerance {
    const char* scene;
    double pixel_rmse, block_rmse;
    int frame = 0;               // the frame compared (its golden: <scene>_<frame:04>.exr)
    double mean_off = 0.02;      // |mean ratio - 1|
    double path_pixel_rmse = 0;  // the path tracer's (64 samples per pixel); 0: 2.5 x pixel_rmse
    bool frozen = true;          // the frozen baseline is compared too
};

constexpr SceneTolerance tolerances[] = {
    {"cornell", 0.06, 0.025},
    {"ball", 0.06, 0.025},
    {"table", 0.06, 0.025},
    {"corridor", 0.21, 0.04},
    {"mirror_room", 0.12, 0.065, 0, 0.02, 0.40},
    {"flythrough", 0.06, 0.025},
    {"glass_move", 0.26, 0.06},
    {"switch_room", 0.14, 0.035, 15},
    // Until the photons trapped in its closed lamp housings stopped leaking into the estimates
    // beside them, the photon methods were 2.3-2.4% too bright here (docs/notes/truth-lamp-housings.md); measured since
    // (with photon paths of up to 64 bounces and each gather ray's own random numbers): per pixel 0.034, blocks 0.016,
    // mean 0.6-0.7% high. The mean within 1%, which the leak fails.
    {"blender_room", 0.06, 0.025, 0, 0.01},
    // Textures, rough plastics, metals, a normal map and a cut-out screen (docs/materials.md).
    // Measured per pixel 0.097, blocks 0.022-0.023, mean 0.6-0.7% high. It was 2.8-3.1% high with
    // blocks at 0.043-0.046 while gather rays that met one triangle of a coated wall shared their
    // Russian-roulette choice (docs/notes/truth-gather-random-numbers.md), and 7-8% with
    // the housing's leak. The mean within 1.5%, which both fail.
    {"blender_textured", 0.12, 0.035, 0, 0.015},
    // Rough glass and absorbing glass (KHR_materials_volume), made by Blender (docs/truth-suite.md):
    // measured per pixel 0.076 (photon), 0.082 (localized); blocks 0.038, 0.046; mean 0.997, 0.994
    // against a golden whose rough glass has its multiple-scattering lobe (without it, 1.4% darker).
    {"blender_glass", 0.10, 0.055, 0, 0.015},
    // Lit from far away through a window marked as a portal (docs/truth-suite.md). With the sun and the sky, measured
    // per pixel 0.079-0.080, blocks 0.026-0.027, mean 1.001 (photon) and 1.005 (localized); 0.132 and 0.036 while a
    // pixel's camera rays and its shadow rays' choice of light were drawn in the same stratified order (the sun was
    // sampled from one slice of each pixel: a bias on the edges of the sunlit faces).
    {"daylit_room", 0.10, 0.035},
    // The sun alone (one light, no such slice): per pixel 0.083, blocks 0.029, mean 1.000; the path tracer 0.221.
    {"daylit_sun", 0.10, 0.037, 0, 0.02, 0.28},
    // Blender's courtyard world over an open ground, its photons aimed at what the camera sees: per pixel 0.049,
    // blocks 0.015-0.016, mean 0.999-1.000; per pixel 0.075 while the world's direct light was sampled by the
    // image's light alone (most samples went below the ground's horizon).
    {"outdoor_hdri", 0.07, 0.022},
    // Lights that move (docs/localized.md#lights-that-move), at frame 15: a torch carried along the corridor among its
    // still lamps, and the daylit room's sun turning. The frozen baseline never corrects its static records, which hold
    // the still lights' light only: in daylit_sweep, whose one light is the moving sun, that is no indirect light.
    {"torch_corridor", 0.21, 0.04, 15},
    {"daylit_sweep", 0.10, 0.037, 15, 0.02, 0.28, false},
};

struct Case {
    SceneTolerance tolerance;
    Method method;
    const char* scene() const { return tolerance.scene; }
};

std::vector<Case> all_cases() {
    std::vector<Case> cases;
    for (const SceneTolerance& t : tolerances)
        for (const Method method : {Method::photon, Method::localized, Method::frozen, Method::path})
            if (method == Method::photon || method == Method::path ||
                (std::string(t.scene) != "cornell" && (method != Method::frozen || t.frozen)))
                cases.push_back({t, method});
    return cases;
}

void PrintTo(const Case& c, std::ostream* os) { *os << c.scene() << " " << method_info(c.method).name; }

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
    return std::string(info.param.scene()) + "_" + std::string(method_info(info.param.method).name);
}

/// Small settings for an 80x60 frame: the photon counts of the golden-image tests.
MethodSettings small_settings(Method method) {
    MethodSettings settings;
    settings.method = method;
    settings.photon.photons = {.global_photons = 100'000, .caustic_photons = 20'000};
    settings.path.samples_per_pixel = 64;
    return settings;
}

struct Rendered {
    Image beauty;
    PixelMask emitters;
    PixelMask glass;  // pixels whose centre sees a dielectric
};

Rendered render_frame(const Case& c) {
    Scene scene(load_scene_desc(source_dir + "/scenes/" + c.scene() + ".json"));
    scene.set_resolution(80, 60);
    if (c.method != Method::path) aim_distant_photons(scene);  // as `steadylight render` does
    const MethodSettings settings = small_settings(c.method);
    const MethodInfo& info = method_info(c.method);
    RayTracer tracer(scene, scene.evaluate(0));
    const Bsdfs bsdfs = make_bsdfs(scene);
    std::optional<StaticSolution> solution;
    const int frame_number = c.tolerance.frame;
    if (info.has_static_pass)
        solution = StaticSolution{run_segment_pass(scene, tracer, scene.segment_of(frame_number), settings.photon)};
    const PlacedFrame frame(scene, tracer, bsdfs, frame_number);
    RenderedFrame rendered =
        info.render_frame(frame.context(), solution ? &*solution : nullptr, settings, AnalysisLayers::made);
    // Every channel of every layer finite (what the writer would otherwise replace by 0).
    EXPECT_EQ(replace_non_finite(rendered.beauty, rendered.layers).count, 0);
    Rendered out{std::move(rendered.beauty), emitter_mask(frame.context()), PixelMask(80 * 60, 0)};
    for (int i = 0; i < 80 * 60; ++i) {
        const Ray ray = frame.context().frame.camera.generate_ray(float(i % 80) + 0.5f, float(i / 80) + 0.5f);
        const std::optional<Hit> hit = tracer.intersect(ray);
        out.glass[size_t(i)] =
            hit && scene.desc().materials[size_t(scene.object(hit->object).material)].type == MaterialType::dielectric;
    }
    return out;
}

/// The mean luminance of `image` over the pixels `where` marks, relative to `reference`'s.
double mean_ratio_where(const Image& image, const Image& reference, const PixelMask& where) {
    PixelMask left_out(where.size());
    for (size_t i = 0; i < where.size(); ++i) left_out[i] = !where[i];
    return image_error(image, reference, left_out).mean_ratio;
}

class TruthSuite : public ::testing::TestWithParam<Case> {};

// The scene's tolerance for the photon methods; the path tracer's 64 samples per pixel are
// noisier (2.5x per pixel, 2x on blocks). The mean within 2% (unless the scene says otherwise), except the frozen
// baseline's, which misses the indirect light that moving objects change by design (4.4% on the corridor): 5%, and 1.5x
// on blocks. Where the camera sees glass, the mean through it within 10%: the dark glass gave 26%.
TEST_P(TruthSuite, FrameAgreesWithTheReference) {
    const Case c = GetParam();
    const Rendered rendered = render_frame(c);
    char golden[64];
    std::snprintf(golden, sizeof golden, "%s_%04d.exr", c.scene(), c.tolerance.frame);
    const Image reference = read_exr(source_dir + "/tests/scenes/golden/" + golden);
    const ImageError e = image_error(rendered.beauty, reference, rendered.emitters);
    std::printf("%s %d %s: per pixel %.4f, 4x4 blocks %.4f, mean ratio %.4f\n", c.scene(), c.tolerance.frame,
                std::string(method_info(c.method).name).c_str(), e.pixel_rmse, e.block_rmse, e.mean_ratio);
    const bool path = c.method == Method::path;
    const double path_pixel_rmse =
        c.tolerance.path_pixel_rmse > 0 ? c.tolerance.path_pixel_rmse : 2.5 * c.tolerance.pixel_rmse;
    EXPECT_LT(e.pixel_rmse, path ? path_pixel_rmse : c.tolerance.pixel_rmse);
    const bool frozen = c.method == Method::frozen;
    EXPECT_LT(e.block_rmse, c.tolerance.block_rmse * (path ? 2 : frozen ? 1.5 : 1));
    EXPECT_NEAR(e.mean_ratio, 1.0, frozen ? std::max(0.05, c.tolerance.mean_off) : c.tolerance.mean_off);
    long glass_pixels = 0;
    for (const uint8_t g : rendered.glass) glass_pixels += g;
    if (glass_pixels > 0) {
        const double glass = mean_ratio_where(rendered.beauty, reference, rendered.glass);
        std::printf("  through glass (%ld pixels): mean ratio %.4f\n", glass_pixels, glass);
        EXPECT_NEAR(glass, 1.0, 0.1);
    }
    testing::keep_pictures_if_failed(rendered.beauty, reference);
}

INSTANTIATE_TEST_SUITE_P(Scenes, TruthSuite, ::testing::ValuesIn(all_cases()), case_name);

}  // namespace
}  // namespace steadylight
