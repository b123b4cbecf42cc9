// The kept direct light (kept_direct_light.h) on its own: what the shading pass logs of a pixel's
// direct light, summed again from the log, is the direct light it shaded, bit for bit; a pixel
// whose camera rays see more than their light samples' sum (an emitter, the empty sky) is not
// kept; and a log that does not fit is refused.
#include "steadylight/passes/kept_direct_light.h"

#include <gtest/gtest.h>

#include <vector>

#include "steadylight/passes/shading_pass.h"
#include "steadylight/scene/shapes.h"
#include "steadylight/shading/frame_context.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

using testing::add_material;
using testing::add_object;
using testing::make_empty_scene;

/// A floor that ends before the horizon, lit by a glowing ball the camera sees, and a box on the
/// floor that shadows part of it: pixels of the floor, of the ball and of the empty sky.
SceneDesc floor_ball_and_sky() {
    SceneDesc desc = make_empty_scene({0, 2, -4}, {0, 0.5f, 2}, 24, 18, 50);
    const int white = add_material(desc, {});
    add_object(desc, make_quad({-3, 0, -3}, {0, 0, 7}, {6, 0, 0}), white);
    add_object(desc, make_box({-1, 0.4f, 1}, {0.8f, 0.8f, 0.8f}), white);
    add_object(desc, Sphere{{0.5f, 1.8f, 2}, 0.3f}, white, {30, 30, 30});
    return desc;
}

/// Shades every pixel's direct light alone, logging it into `kept`, and notes what it shaded.
class LoggingSource : public PixelSource {
public:
    LoggingSource(KeptDirectLight& kept, int width) : m_kept(kept), m_width(width) {}
    std::vector<Rgb> shaded;

    Shading begin(int, int, size_t, PixelSums&) override { return Shading::direct_only; }
    DirectLightLog* direct_light_log(int x, int y, size_t pixel) override { return m_kept.log_for(x, y, pixel); }
    void finish(size_t pixel, PixelSums& sums) override {
        shaded[pixel] = sums.direct;
        m_kept.keep(int(pixel % size_t(m_width)), int(pixel / size_t(m_width)), pixel);
    }

private:
    KeptDirectLight& m_kept;
    int m_width;
};

TEST(KeptDirectLight, SumsAgainWhatTheShadingLoggedBitForBit) {
    const Scene scene(floor_ball_and_sky());
    const PreparedFrame frame(scene, 0);
    const Camera& camera = frame.context().frame.camera;
    ShadingSettings settings;
    settings.samples_per_pixel = 4;
    KeptDirectLight kept;
    kept.make(camera.width, camera.height, settings.samples_per_pixel, settings.direct_samples, 1e9);
    LoggingSource source(kept, camera.width);
    source.shaded.resize(size_t(camera.width) * size_t(camera.height));
    const auto none = [](auto&&...) { return Rgb{}; };
    shade_frame(frame.context(), settings, PhotonMap{}, none, none, Visibility::everything, &source);
    long summed = 0, refused = 0, lit = 0;
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            const size_t pixel = size_t(y) * size_t(camera.width) + size_t(x);
            const std::byte* kept_pixel = kept.find(x, y);
            if (!kept_pixel) {
                ++refused;
                EXPECT_FALSE(kept.log_for(x, y, pixel)) << "a refused pixel is not logged again";
                continue;
            }
            const Rgb again = kept.direct_light(kept_pixel, frame.context().tracer);
            const Rgb& shaded = source.shaded[pixel];
            ASSERT_TRUE(again.r == shaded.r && again.g == shaded.g && again.b == shaded.b) << x << " " << y;
            ++summed;
            lit += shaded.r > 0;
        }
    EXPECT_EQ(summed, kept.pixels());
    // The floor's pixels, lit and in the box's shadow, are kept; the ball's and the sky's are not.
    EXPECT_GT(lit, camera.width * camera.height / 4);
    EXPECT_GT(summed, lit);
    EXPECT_GT(refused, camera.width * camera.height / 10);
}

TEST(KeptDirectLight, RefusesLogsThatAreNotWholeOrDoNotFit) {
    KeptDirectLight kept;
    const int width = 20, samples = 2;
    const double max_bytes = 2500;  // a tile's bookkeeping and a few pixels
    kept.make(width, width, samples, 2, max_bytes);
    // Logs pixel (x, y): `rays` camera rays of a light sample each, spoiled or not.
    const auto log_pixel = [&](int x, int y, int rays, bool spoil) {
        const size_t pixel = size_t(y) * size_t(width) + size_t(x);
        DirectLightLog* log = kept.log_for(x, y, pixel);
        if (!log) return false;
        for (int ray = 0; ray < rays; ++ray) {
            log->add_ray({0, 0, 0}, {0, 1, 0});
            log->add_sample({0, 5, 0}, false, {1, 1, 1});
        }
        if (spoil) log->spoil();
        kept.keep(x, y, pixel);
        return true;
    };
    EXPECT_TRUE(log_pixel(0, 0, samples, false));
    EXPECT_TRUE(kept.find(0, 0));
    EXPECT_FALSE(kept.log_for(0, 0, 0)) << "kept: not logged again";
    EXPECT_TRUE(log_pixel(1, 0, samples - 1, false));  // a camera ray not logged
    EXPECT_TRUE(log_pixel(2, 0, samples, true));
    EXPECT_FALSE(kept.find(1, 0));
    EXPECT_FALSE(kept.find(2, 0));
    EXPECT_FALSE(kept.log_for(1, 0, 1)) << "refused: not logged again";
    EXPECT_FALSE(kept.log_for(2, 0, 2)) << "refused: not logged again";
    // In another tile the bookkeeping would pass the bytes allowed: nothing is kept there.
    EXPECT_TRUE(log_pixel(0, shading_tile_size, samples, false));
    EXPECT_FALSE(kept.find(0, shading_tile_size));
    EXPECT_EQ(kept.pixels(), 1);
    EXPECT_LE(double(kept.bytes()), max_bytes);
    EXPECT_GT(kept.bytes(), 0u);
}

}  // namespace
}  // namespace steadylight
