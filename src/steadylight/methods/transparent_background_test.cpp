// A transparent background (--transparent-background, Camera::transparent_background) in every
// method: alpha is the share of a pixel's camera rays that meet a surface, the world the camera
// sees directly is left out (premultiplied colours: black where alpha is 0), and the world seen
// through glass and in mirrors stays, as Cycles keeps it by default.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>

#include "steadylight/methods/method.h"
#include "steadylight/passes/segment_pass.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

constexpr int samples = 4;

MethodSettings small_settings(Method method) {
    MethodSettings settings;
    settings.method = method;
    settings.photon.photons = {.global_photons = 20'000, .caustic_photons = 5'000};
    settings.photon.shading.samples_per_pixel = settings.path.samples_per_pixel = samples;
    return settings;
}

Scene balls(bool transparent) {
    Scene scene(testing::balls_before_the_world());
    scene.set_transparent_background(transparent);
    return scene;
}

/// Frame 0 of `scene` by `method`, after its static pass when it has one.
RenderedFrame render(const Scene& scene, Method method) {
    const MethodSettings settings = small_settings(method);
    const MethodInfo& info = method_info(method);
    std::optional<StaticSolution> solution;
    if (info.has_static_pass) {
        RayTracer tracer(scene, scene.evaluate(0));
        solution.emplace(StaticSolution{run_segment_pass(scene, tracer, {0, 0}, settings.photon)});
    }
    const PreparedFrame frame(scene, 0);
    return info.render_frame(frame.context(), solution ? &*solution : nullptr, settings, AnalysisLayers::made);
}

/// The pixel where the camera sees world point `p`.
std::pair<int, int> pixel_of(const Scene& scene, Vec3 p) {
    const Vec2 at = scene.evaluate(0).camera.project(p).value();
    return {int(at.x), int(at.y)};
}

float alpha_at(const RenderedFrame& frame, std::pair<int, int> pixel) {
    return frame.alpha->at(pixel.first, pixel.second).r;
}

TEST(TransparentBackground, AlphaIsTheShareOfCameraRaysThatMeetASurfaceInEveryMethod) {
    const Scene scene = balls(true);
    const auto grey = pixel_of(scene, {-1.4f, 0.3f, 0}), glass = pixel_of(scene, {0, 0.3f, 0}),
               mirror = pixel_of(scene, {1.4f, 0.3f, 0});
    for (const MethodInfo& info : methods()) {
        const RenderedFrame frame = render(scene, info.method);
        ASSERT_TRUE(frame.alpha.has_value()) << info.name;
        ASSERT_EQ(frame.alpha->pixels.size(), frame.beauty.pixels.size()) << info.name;
        EXPECT_EQ(alpha_at(frame, grey), 1) << info.name;
        // Glass and mirrors are surfaces: the world seen through them and in them stays.
        EXPECT_EQ(alpha_at(frame, glass), 1) << info.name;
        EXPECT_EQ(alpha_at(frame, mirror), 1) << info.name;
        for (const std::pair<int, int>& pixel : {glass, mirror}) {
            const Rgb seen = frame.beauty.at(pixel.first, pixel.second);
            EXPECT_GT(seen.b, seen.r) << info.name << ": the blue world seen through glass and in a mirror";
        }
        int empty = 0, edges = 0;
        for (size_t i = 0; i < frame.alpha->pixels.size(); ++i) {
            const float alpha = frame.alpha->pixels[i].r;
            ASSERT_EQ(alpha * samples, std::round(alpha * samples)) << info.name << " pixel " << i;
            edges += alpha > 0 && alpha < 1;
            if (alpha > 0) continue;
            ++empty;
            // Nothing of the world the camera sees directly, in the beauty or any layer of light.
            ASSERT_EQ(frame.beauty.pixels[i], Rgb{}) << info.name << " pixel " << i;
            for (const NamedImage& layer : frame.layers) {
                if (layer.grey()) continue;
                ASSERT_EQ(layer.colour_at(i), Rgb{}) << info.name << " " << layer.name;
            }
        }
        EXPECT_GT(empty, int(frame.alpha->pixels.size()) / 2) << info.name;
        EXPECT_GT(edges, 20) << info.name << ": the balls' outlines";
    }
}

TEST(TransparentBackground, LeavesOutOnlyTheWorldTheCameraSeesDirectly) {
    const Scene opaque_scene = balls(false), clear_scene = balls(true);
    for (const MethodInfo& info : methods()) {
        const RenderedFrame opaque = render(opaque_scene, info.method), clear = render(clear_scene, info.method);
        EXPECT_FALSE(opaque.alpha.has_value()) << info.name;
        ASSERT_TRUE(clear.alpha.has_value()) << info.name;
        const Rgb world{0.2f, 0.3f, 0.5f};
        int covered = 0;
        for (size_t i = 0; i < clear.alpha->pixels.size(); ++i) {
            const float alpha = clear.alpha->pixels[i].r;
            if (alpha == 0) {
                for (int c = 0; c < 3; ++c) ASSERT_NEAR(opaque.beauty.pixels[i][c], world[c], 1e-6f) << info.name;
            } else if (alpha == 1) {
                // Every camera ray met a surface: the pixel is the opaque render's, bit for bit.
                ++covered;
                ASSERT_EQ(clear.beauty.pixels[i], opaque.beauty.pixels[i]) << info.name << " pixel " << i;
                for (size_t l = 0; l < clear.layers.size(); ++l)
                    ASSERT_EQ(clear.layers[l].colour_at(i), opaque.layers[l].colour_at(i))
                        << info.name << " " << clear.layers[l].name;
            } else {
                // An edge: the world's share of the pixel is gone.
                EXPECT_LT(luminance(clear.beauty.pixels[i]), luminance(opaque.beauty.pixels[i])) << info.name;
            }
        }
        EXPECT_GT(covered, 50) << info.name;
    }
}

TEST(TransparentBackground, SameOnOneAndTwoThreads) {
    const Scene scene = balls(true);
    for (const Method method : {Method::localized, Method::path}) {
        RenderedFrame one, two;
        tbb::task_arena(1).execute([&] { one = render(scene, method); });
        tbb::task_arena(2).execute([&] { two = render(scene, method); });
        EXPECT_TRUE(one.alpha->pixels == two.alpha->pixels) << method_info(method).name;
        EXPECT_TRUE(one.beauty.pixels == two.beauty.pixels) << method_info(method).name;
    }
}

}  // namespace
}  // namespace steadylight
