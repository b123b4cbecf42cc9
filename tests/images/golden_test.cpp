// The photon method's frame 0 of cornell and BALL against converged path-traced references
// (tests/scenes/golden/, scripts/make_golden.sh: 80x60, 4096 samples per pixel). A frame that
// fails leaves its picture, the reference and their difference under the build folder
// (support/failure_pictures.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "steadylight/methods/photon_mapping.h"
#include "steadylight/output/image_writer.h"
#include "support/failure_pictures.h"

namespace steadylight {
namespace {

const std::string source_dir = STEADYLIGHT_SOURCE_DIR;

/// Display-referred agreement: Y = luminance clamped at 1, as the PNG shows it. Unclamped, the
/// anti-aliasing noise of the light's edge pixels (radiance 17 next to 0.1) dominates.
struct Agreement {
    double relative_rmse;  // sqrt(mean((Y - Y_ref)^2)) / mean(Y_ref)
    double relative_bias;  // (mean(Y) - mean(Y_ref)) / mean(Y_ref)
};

Agreement compare(const Image& image, const Image& reference) {
    double sum2 = 0, sum = 0, sum_ref = 0;
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const double y = std::min(1.0f, luminance(image.pixels[i]));
        const double y_ref = std::min(1.0f, luminance(reference.pixels[i]));
        sum2 += (y - y_ref) * (y - y_ref);
        sum += y;
        sum_ref += y_ref;
    }
    const double n = double(image.pixels.size()), mean_ref = sum_ref / n;
    return {std::sqrt(sum2 / n) / mean_ref, (sum - sum_ref) / n / mean_ref};
}

/// Against the converged path-traced references (scripts/make_golden.sh, 4096 spp). Measured:
/// cornell 4.5% relative RMSE and +0.2% bias, BALL about the same. The RMSE is mostly noise of the
/// 16 camera rays x 4 shadow rays per pixel (soft shadows, anti-aliased edges at 80 x 60); the
/// bias comes from density estimation and cache interpolation. We allow 7% RMSE and 2% bias: a
/// broken term fails by far (the indirect light is ~30% of these images; the 1 cm-offset shadow
/// ray bug that hid the light from distant points made the reference 10% darker).
void expect_agrees_with_path_tracer(const std::string& name) {
    Scene scene(load_scene_desc(source_dir + "/scenes/" + name + ".json"));
    scene.set_resolution(80, 60);
    PhotonMappingSettings settings;  // small but representative for an 80 x 60 frame
    settings.photons = {.global_photons = 100'000, .caustic_photons = 20'000};
    const PhotonFrame frame = render_photon_mapped(PreparedFrame(scene, 0).context(), settings);
    const Image reference = read_exr(source_dir + "/tests/scenes/golden/" + name + "_0000.exr");
    const Agreement a = compare(frame.beauty, reference);
    EXPECT_LT(a.relative_rmse, 0.07) << name;
    EXPECT_LT(std::abs(a.relative_bias), 0.02) << name;
    std::printf("%s: relative RMSE %.4f, relative bias %+.4f, records %ld\n", name.c_str(), a.relative_rmse,
                a.relative_bias, frame.stats.irradiance_records);
    testing::keep_pictures_if_failed(frame.beauty, reference);
}

TEST(PhotonMapping, CornellAgreesWithPathTracer) { expect_agrees_with_path_tracer("cornell"); }

TEST(PhotonMapping, BallFrameZeroAgreesWithPathTracer) { expect_agrees_with_path_tracer("ball"); }

}  // namespace
}  // namespace steadylight
