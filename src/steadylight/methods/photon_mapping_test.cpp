#include "steadylight/methods/photon_mapping.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>

#include "steadylight/passes/photon_gather.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

const std::string source_dir = STEADYLIGHT_SOURCE_DIR;

Scene load_scene(const std::string& name, int width, int height) {
    Scene scene(load_scene_desc(source_dir + "/scenes/" + name + ".json"));
    scene.set_resolution(width, height);
    return scene;
}

PhotonFrame render(const Scene& scene, int frame, const PhotonMappingSettings& settings) {
    return render_photon_mapped(PreparedFrame(scene, frame).context(), settings);
}

/// Small but representative settings for an 80 x 60 test frame.
PhotonMappingSettings test_settings() {
    PhotonMappingSettings settings;
    settings.photons.global_photons = 100'000;
    settings.photons.caustic_photons = 20'000;
    settings.shading.samples_per_pixel = 16;
    return settings;
}

/// Camera rays through absorbing glass (the shading pass's specular chain) lose what the path
/// tracer's do: light that crosses 1 unit of glass that keeps c over 0.5 units is c^2.
TEST(PhotonMapping, AbsorbingGlassTransmitsItsColourToThePowerOfTheDistance) {
    const Rgb c{0.8f, 0.5f, 0.2f};
    const Scene scene(testing::absorbing_ball_before_light(c));
    const Image image = render(scene, 0, test_settings()).beauty;
    for (const Rgb& L : image.pixels)
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(L[i], c[i] * c[i], 0.01f * c[i] * c[i]) << "channel " << i;
}

TEST(PhotonMapping, LayersSumToTheBeauty) {
    const PhotonFrame frame = render(load_scene("ball", 40, 30), 0, test_settings());
    for (size_t i = 0; i < frame.beauty.pixels.size(); ++i) {
        const Rgb sum =
            frame.direct.pixels[i] + frame.indirect.pixels[i] + frame.caustic.pixels[i] + frame.specular.pixels[i];
        EXPECT_NEAR(sum.g, frame.beauty.pixels[i].g, 1e-4f * (1 + sum.g));
    }
    EXPECT_GT(frame.stats.irradiance_records, 10);
}

TEST(PhotonMapping, TableShowsACausticUnderTheGlassSphere) {
    const Scene scene = load_scene("table", 160, 120);
    PhotonMappingSettings settings = test_settings();
    settings.photons.caustic_photons = 200'000;
    const PhotonFrame frame = render(scene, 0, settings);
    // The brightest caustic pixel shows the table top next to the sphere's base.
    size_t brightest = 0;
    for (size_t i = 0; i < frame.caustic.pixels.size(); ++i)
        if (luminance(frame.caustic.pixels[i]) > luminance(frame.caustic.pixels[brightest])) brightest = i;
    ASSERT_GT(luminance(frame.caustic.pixels[brightest]), 0.5f);
    const FrameState state = scene.evaluate(0);
    const RayTracer tracer(scene, state);
    const Ray ray = state.camera.generate_ray(float(brightest % 160) + 0.5f, float(brightest / 160) + 0.5f);
    const std::optional<Hit> hit = tracer.intersect(ray);
    ASSERT_TRUE(hit);
    const Vec3 p = ray.o + ray.d * hit->t;
    EXPECT_NEAR(p.y, 0.80f, 0.01f);
    EXPECT_LT(length(Vec3{p.x - 4.6f, 0, p.z - 3.3f}), 0.6f) << to_string(p);
}

// What the camera sees through TABLE's glass sphere gets cache records like the rest: a pixel
// whose centre sees the glass has its cache point on the diffuse surface behind it, so its camera
// rays find records there instead of each gathering anew (which cost about 6 s a frame).
TEST(PhotonMapping, PointsSeenThroughGlassAreCached) {
    const Scene scene = load_scene("table", 64, 48);
    const PreparedFrame frame(scene, 0);
    const FrameContext& context = frame.context();
    int through_glass = 0, cached = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            const std::optional<Hit> hit =
                context.tracer.intersect(context.frame.camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f));
            if (!hit || !context.bsdf_of(hit->object).is_delta()) continue;
            ++through_glass;
            const std::optional<CachePoint> point = cache_point_at(context, Visibility::everything, x, y);
            if (!point) continue;
            EXPECT_TRUE(context.bsdf_of(point->object).is_diffuse());
            EXPECT_NE(point->object, hit->object);
            cached += 1;
        }
    ASSERT_GT(through_glass, 20);
    EXPECT_GT(cached, through_glass * 9 / 10);
    const PhotonMappingSettings settings = test_settings();
    const PhotonFrame shaded = render(scene, 0, settings);
    // Every camera ray through the glass also follows its reflections, which mostly land where
    // no record reaches and gather there, roughly (32 rays): measured 591 such gathers for 464
    // camera rays. The refracted view is cached: gathered anew, it would cost each of those
    // camera rays a full gather (512 rays), five times this bound.
    const long rays_per_gather = settings.gather.theta_strata * settings.gather.phi_strata;
    const long fallback_rays = shaded.stats.gather_rays - shaded.stats.irradiance_records * rays_per_gather;
    EXPECT_GT(fallback_rays, 0);
    EXPECT_LT(fallback_rays, through_glass * settings.shading.samples_per_pixel * rays_per_gather / 5);
}

Rgb mean(const Image& image) {
    Rgb sum;
    for (const Rgb& p : image.pixels) sum += p;
    return sum / float(image.pixels.size());
}

/// The ceiling lamp of tests/scenes/light_switch.json, the only light here, is off until frame 10.
TEST(PhotonMapping, LightSwitchedOnMidAnimationIsBlackThenLit) {
    SceneDesc desc = load_scene_desc(source_dir + "/tests/scenes/light_switch.json");
    desc.point_lights.clear();
    const Scene scene(std::move(desc));
    PhotonMappingSettings settings = test_settings();
    settings.photons.global_photons = 20'000;
    const PhotonFrame off = render(scene, 9, settings), on = render(scene, 10, settings);
    EXPECT_EQ(off.stats.global_photons_stored, 0);
    for (const Rgb& pixel : off.beauty.pixels) EXPECT_EQ(pixel, Rgb{});
    EXPECT_GT(on.stats.global_photons_stored, 0);
    std::printf("lit: mean direct %.4f, mean indirect %.4f\n", mean(on.direct).r, mean(on.indirect).r);
    EXPECT_GT(mean(on.direct).r, 0.05f);
    EXPECT_GT(mean(on.indirect).r, 0.03f);
}

TEST(PhotonMapping, SameFrameTwiceAndOnOneOrTwoThreadsIsBitIdentical) {
    const Scene scene = load_scene("table", 48, 36);
    PhotonMappingSettings settings = test_settings();
    settings.photons.global_photons = 20'000;
    PhotonFrame one, two, again;
    tbb::task_arena(1).execute([&] { one = render(scene, 5, settings); });
    tbb::task_arena(2).execute([&] { two = render(scene, 5, settings); });
    tbb::task_arena(2).execute([&] { again = render(scene, 5, settings); });
    EXPECT_TRUE(one.beauty.pixels == two.beauty.pixels);
    EXPECT_TRUE(two.beauty.pixels == again.beauty.pixels);
    EXPECT_EQ(one.stats.irradiance_records, two.stats.irradiance_records);
}

}  // namespace
}  // namespace steadylight
