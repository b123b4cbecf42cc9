#include "steadylight/methods/path_tracer.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "steadylight/scene/scene_desc.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

using testing::add_material;
using testing::add_object;
using testing::make_empty_scene;

Image render(const Scene& scene, int frame, const PathTracerSettings& settings) {
    return render_path_traced(PreparedFrame(scene, frame).context(), settings);
}

Rgb mean(const Image& image) {
    Rgb sum;
    for (const Rgb& p : image.pixels) sum += p;
    return sum / float(image.pixels.size());
}

/// Inside a closed diffuse sphere of albedo a that emits Le everywhere, the radiance is
/// Le / (1 - a) in every direction (pbrt-v4 integrators_test "furnace").
TEST(PathTracer, WhiteFurnaceGivesLeOverOneMinusAlbedo) {
    for (const float albedo : {0.5f, 0.8f}) {
        SceneDesc desc = make_empty_scene({0, 0, 0}, {0, 0, -1}, 16, 16, 90);
        const int material = add_material(desc, {.reflectance = {albedo, albedo, albedo}});
        const float Le = 0.5f;
        add_object(desc, Sphere{{0.2f, -0.1f, 0.1f}, 1}, material, {Le, Le, Le});
        desc.objects[0].two_sided_emission = true;
        const Scene scene(std::move(desc));
        const Rgb L = mean(render(scene, 0, {.samples_per_pixel = 256}));
        const float expected = Le / (1 - albedo);
        EXPECT_NEAR(L.r, expected, 0.01f * expected) << "albedo " << albedo;
        EXPECT_NEAR(L.g, expected, 0.01f * expected) << "albedo " << albedo;
    }
}

/// A diffuse floor under a point light: L = rho / pi * I cos(theta) / d^2, no indirect light.
TEST(PathTracer, PointLightOverDiffuseFloorMatchesInverseSquareLaw) {
    SceneDesc desc = make_empty_scene({0, 1, 0}, {0, 0, 0}, 1, 1, 1);
    add_object(desc, make_quad({-50, 0, -50}, {0, 0, 100}, {100, 0, 0}), add_material(desc, {.reflectance = {0.5f, 0.5f, 0.5f}}));
    desc.point_lights.push_back({.position = {1, 2, 0}, .intensity = {10, 10, 10}});
    const Scene scene(std::move(desc));
    const Rgb L = render(scene, 0, {.samples_per_pixel = 16}).at(0, 0);
    const float d2 = 5, cos_theta = 2 / std::sqrt(d2);
    EXPECT_NEAR(L.r, 0.5f / pi * 10 * cos_theta / d2, 2e-3f);
}

/// A small quad light far above a diffuse floor, seen at a slant: L = rho / pi * Le A cos_r cos_l
/// / d^2. Shadow rays must reach the light itself without being stopped by it, also far from the
/// origin where ray offsets are large (the scene sits at x = 100).
TEST(PathTracer, SmallQuadLightOverDiffuseFloorMatchesInverseSquareLaw) {
    SceneDesc desc = make_empty_scene({103, 0.5f, 0}, {103, 0, 0}, 1, 1, 1);
    const int white = add_material(desc, {.reflectance = {0.5f, 0.5f, 0.5f}});
    add_object(desc, make_quad({50, 0, -50}, {0, 0, 100}, {100, 0, 0}), white);
    add_object(desc, make_quad({99.95f, 5, -0.05f}, {0.1f, 0, 0}, {0, 0, 0.1f}), white, {100, 100, 100});
    const Scene scene(std::move(desc));
    const Rgb L = render(scene, 0, {.samples_per_pixel = 64, .max_depth = 1}).at(0, 0);
    const float d2 = 3 * 3 + 5 * 5, cos = 5 / std::sqrt(d2);
    const float expected = 0.5f / pi * 100 * 0.01f * cos * cos / d2;
    EXPECT_NEAR(L.r, expected, 0.01f * expected);
}

/// A lamp whose intensity track doubles at frame 1 lights a floor and a wall (direct and
/// indirect light): frame 0 equals the same scene with a fixed intensity bit for bit, and frame 1
/// is exactly twice it. Same frame, same random numbers; doubling is exact in floating point.
TEST(PathTracer, LampIntensityTrackScalesTheImageExactly) {
    SceneDesc desc = make_empty_scene({0, 1, 3}, {0, 0.5f, 0}, 12, 8);
    desc.frame_count = 2;
    desc.fps = 1;
    const int white = add_material(desc, {.reflectance = {0.5f, 0.6f, 0.7f}});
    add_object(desc, make_quad({-5, 0, -5}, {0, 0, 10}, {10, 0, 0}), white);
    add_object(desc, make_quad({-5, 0, -1}, {10, 0, 0}, {0, 5, 0}), white);
    desc.point_lights.push_back({.position = {0.5f, 2, 0}, .intensity = {3, 3, 3}});
    const Scene fixed(desc);
    desc.point_lights[0].intensity_track = Track<Rgb>{Interpolation::step, {0, 1}, {Rgb{3, 3, 3}, Rgb{6, 6, 6}}};
    const Scene switched(std::move(desc));
    const PathTracerSettings settings{.samples_per_pixel = 4};
    const Image reference = render(fixed, 1, settings);
    EXPECT_TRUE(render(switched, 0, settings).pixels == render(fixed, 0, settings).pixels);
    const Image doubled = render(switched, 1, settings);
    EXPECT_GT(mean(reference).r, 0.0f);
    for (size_t i = 0; i < reference.pixels.size(); ++i) EXPECT_EQ(doubled.pixels[i], reference.pixels[i] * 2.0f) << "pixel " << i;
}

TEST(PathTracer, SameImageForOneAndTwoThreads) {
    Scene scene(load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/ball.json"));
    scene.set_resolution(40, 30);
    const PathTracerSettings settings{.samples_per_pixel = 4};
    Image one, two;
    tbb::task_arena(1).execute([&] { one = render(scene, 7, settings); });
    tbb::task_arena(2).execute([&] { two = render(scene, 7, settings); });
    ASSERT_EQ(one.pixels.size(), two.pixels.size());
    for (size_t i = 0; i < one.pixels.size(); ++i) ASSERT_EQ(one.pixels[i], two.pixels[i]) << "pixel " << i;
}

TEST(PathTracer, SameFrameTwiceIsBitIdentical) {
    Scene scene(load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/table.json"));
    scene.set_resolution(32, 24);
    const Image a = render(scene, 3, {.samples_per_pixel = 2});
    const Image b = render(scene, 3, {.samples_per_pixel = 2});
    EXPECT_TRUE(a.pixels == b.pixels);
}

}  // namespace
}  // namespace steadylight
