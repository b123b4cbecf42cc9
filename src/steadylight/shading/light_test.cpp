#include "steadylight/shading/light.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <optional>
#include <utility>

#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "steadylight/scene/shapes.h"

namespace steadylight {
namespace {

constexpr Vec3 origin{0, 0, 0};

SceneDesc empty_scene() {
    SceneDesc desc;
    desc.materials.push_back(MaterialDesc{});
    desc.camera.placement = {AnimatedTrs{}};
    return desc;
}

ObjectDesc object(Geometry geometry, Rgb emission, bool two_sided = false) {
    ObjectDesc o;
    o.name = "light";
    o.geometry = std::move(geometry);
    o.emission = emission;
    o.two_sided_emission = two_sided;
    o.placement = {AnimatedTrs{}};
    o.material = 0;
    return o;
}

/// A size x size square at height z centred above (x, y), its front facing down (-z).
ObjectDesc ceiling_light(float size, float z, Rgb emission, float x = 0, float y = 0, bool two_sided = false) {
    const Vec3 corner{x - size / 2, y - size / 2, z};
    return object(make_quad(corner, {0, size, 0}, {size, 0, 0}), emission, two_sided);
}

/// A scene built from `desc` and its lights at `frame_index`. Not copyable: the lights refer to the scene.
struct Lit {
    explicit Lit(SceneDesc desc, int frame_index = 0)
        : scene(std::move(desc)), frame(scene.evaluate(frame_index)), lights(scene, frame) {}
    Lit(const Lit&) = delete;
    Lit& operator=(const Lit&) = delete;

    Scene scene;
    FrameState frame;
    LightSet lights;
};

SceneDesc scene_with(std::initializer_list<ObjectDesc> objects) {
    SceneDesc desc = empty_scene();
    desc.objects = objects;
    return desc;
}

/// Where the ray from ref along dir first meets the light, and the light's normal there.
using HitFn = std::function<std::optional<std::pair<Vec3, Vec3>>(Vec3 ref, Vec3 dir)>;

/// ∫ pdf_emitter(object, ref, p(w), n) dw over the sphere of directions w, estimated with
/// stratified uniform directions (n x n strata, one jittered sample each).
double integrate_pdf(const LightSet& lights, int object, Vec3 ref, const HitFn& hit, int n = 1000) {
    Pcg32 rng(9);
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 w = sample_uniform_sphere({(i + rng.next_float()) / n, (j + rng.next_float()) / n});
            if (const auto h = hit(ref, w)) sum += lights.pdf_emitter(object, ref, h->first, h->second);
        }
    return sum / (double(n) * n * uniform_sphere_pdf());
}

/// Monte Carlo irradiance at ref with normal n from next-event samples: E = mean of Li cos / pdf.
double irradiance(const LightSet& lights, Vec3 ref, Vec3 n, int samples) {
    Pcg32 rng(10);
    double sum = 0;
    for (int i = 0; i < samples; ++i) {
        const std::optional<LightSample> s = lights.sample(ref, rng.next_float(), rng.next_vec2());
        if (s) sum += luminance(s->Li) * std::max(0.0f, dot(s->wi, n)) / s->pdf;
    }
    return sum / samples;
}

/// Form factor from a differential area to a parallel a x b rectangle at distance c, with the
/// normal of the area through one corner of the rectangle (Howell's catalogue, B-3).
double corner_form_factor(double a, double b, double c) {
    const double x = a / c, y = b / c, sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
    return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * pi);
}

std::optional<LightSample> sample_once(const LightSet& lights, Vec3 ref, float u_select = 0.5f) {
    return lights.sample(ref, u_select, {0.3f, 0.6f});
}

TEST(LightSet, SceneWithoutEmittersHasNoLights) {
    const Lit lit(scene_with({ceiling_light(1, 1, Rgb{})}));
    EXPECT_TRUE(lit.lights.empty());
    EXPECT_FALSE(sample_once(lit.lights, origin).has_value());
    EXPECT_EQ(lit.lights.pdf_emitter(0, origin, {0, 0, 1}, {0, 0, -1}), 0.0f);
}

TEST(LightSet, QuadLightRadianceIsItsEmissionOnTheFrontSide) {
    const Rgb emission{1, 2, 3};
    const Lit lit(scene_with({ceiling_light(1, 1, emission)}));
    Pcg32 rng(1);
    for (int i = 0; i < 100; ++i) {
        const std::optional<LightSample> s = lit.lights.sample(origin, rng.next_float(), rng.next_vec2());
        ASSERT_TRUE(s.has_value());
        EXPECT_EQ(s->Li, emission);
        EXPECT_FALSE(s->is_delta);
        EXPECT_NEAR(s->p.z, 1.0f, 1e-6f);
        EXPECT_LE(std::max(std::abs(s->p.x), std::abs(s->p.y)), 0.5f + 1e-6f) << "on the quad";
        EXPECT_NEAR(s->n.z, -1.0f, 1e-6f);
        EXPECT_NEAR(length(s->p - origin), s->distance, 1e-5f);
        EXPECT_NEAR(dot(s->wi, (s->p - origin) / s->distance), 1.0f, 1e-5f);
    }
}

TEST(LightSet, OneSidedQuadLightIsDarkBehind) {
    const Lit lit(scene_with({ceiling_light(1, 1, {1, 1, 1})}));
    Pcg32 rng(2);
    for (int i = 0; i < 100; ++i)
        EXPECT_FALSE(lit.lights.sample({0.2f, -0.1f, 2}, rng.next_float(), rng.next_vec2()).has_value());
}

TEST(LightSet, TwoSidedQuadLightShinesFromBothSides) {
    const Rgb emission{1, 2, 3};
    const Lit lit(scene_with({ceiling_light(1, 1, emission, 0, 0, true)}));
    for (const Vec3 ref : {origin, Vec3{0.2f, -0.1f, 2}}) {
        const std::optional<LightSample> s = sample_once(lit.lights, ref);
        ASSERT_TRUE(s.has_value());
        EXPECT_EQ(s->Li, emission);
    }
}

TEST(LightSet, SamplePdfMatchesPdfEmitter) {
    const Lit lit(scene_with({ceiling_light(1, 1, {1, 1, 1}), object(Sphere{{3, 0, 1}, 0.5f}, {2, 2, 2})}));
    Pcg32 rng(3);
    int checked = 0;
    for (int i = 0; i < 1000; ++i) {
        const Vec3 ref{rng.next_float() - 0.5f, rng.next_float() - 0.5f, -rng.next_float()};
        const std::optional<LightSample> s = lit.lights.sample(ref, rng.next_float(), rng.next_vec2());
        if (!s) continue;  // the back of the sphere
        const int light = s->p.x > 2 ? 1 : 0;
        EXPECT_NEAR(lit.lights.pdf_emitter(light, ref, s->p, s->n), s->pdf, 1e-4f * s->pdf);
        ++checked;
    }
    EXPECT_GT(checked, 500);
}

TEST(LightSet, QuadLightPdfIntegratesToOneOverSolidAngle) {
    const Vec3 corner{-0.5f, -0.3f, 1}, edge_u{0, 1, 0}, edge_v{1.5f, 0, 0};
    const Lit lit(scene_with({object(make_quad(corner, edge_u, edge_v), {1, 1, 1})}));
    const HitFn hit_quad = [&](Vec3 ref, Vec3 dir) -> std::optional<std::pair<Vec3, Vec3>> {
        const Vec3 n = normalize(cross(edge_u, edge_v));
        const float t = dot(corner - ref, n) / dot(dir, n);
        if (!(t > 0)) return std::nullopt;
        const Vec3 p = ref + dir * t;
        const float a = dot(p - corner, edge_u) / length2(edge_u), b = dot(p - corner, edge_v) / length2(edge_v);
        if (a < 0 || a > 1 || b < 0 || b > 1) return std::nullopt;
        return std::pair{p, n};
    };
    for (const Vec3 ref : {origin, Vec3{0.3f, 0.2f, 0.5f}, Vec3{2, -1, 0}})
        EXPECT_NEAR(integrate_pdf(lit.lights, 0, ref, hit_quad), 1.0, 0.02) << to_string(ref);
}

// Seen from outside, a sphere light is sampled over the cone of directions that meet it, so over
// those directions the pdf integrates to 1 (area samples spread over the whole sphere gave the
// visible cap's share, (1 - R / D) / 2, a third here, and wasted the rest).
TEST(LightSet, SphereLightPdfIntegratesToOneOverTheConeThatSeesIt) {
    const Vec3 center{0, 0, 3};
    const float radius = 1;
    const Lit lit(scene_with({object(Sphere{center, radius}, {1, 1, 1})}));
    const HitFn hit_sphere = [&](Vec3 ref, Vec3 dir) -> std::optional<std::pair<Vec3, Vec3>> {
        const Vec3 oc = ref - center;
        const float b = dot(oc, dir), disc = b * b - (length2(oc) - radius * radius);
        if (disc < 0 || -b - std::sqrt(disc) <= 0) return std::nullopt;
        const Vec3 p = ref + dir * (-b - std::sqrt(disc));
        return std::pair{p, normalize(p - center)};
    };
    EXPECT_NEAR(integrate_pdf(lit.lights, 0, origin, hit_sphere), 1.0, 0.02);
    // Every sample lands on the near side, facing the point.
    Pcg32 rng(5);
    for (int i = 0; i < 1000; ++i) {
        const std::optional<LightSample> s = lit.lights.sample(origin, 0.5f, rng.next_vec2());
        ASSERT_TRUE(s);
        EXPECT_NEAR(length(s->p - center), radius, 1e-4f);
        EXPECT_LT(dot(s->n, s->wi), 1e-4f);
    }
}

// A sphere of radiance L whose centre is straight above a receiver facing it gives
// E = pi L sin^2(theta_max) = pi L (R / D)^2; its cone samples differ only by the cosine.
TEST(LightSet, SphereLightIrradianceMatchesItsConeWithLittleSpread) {
    const float radiance = 3, radius = 0.5f, distance = 1.5f;
    const Lit lit(scene_with({object(Sphere{{0, 0, distance}, radius}, {radiance, radiance, radiance})}));
    const double expected = pi * radiance * (radius / distance) * (radius / distance);
    EXPECT_NEAR(irradiance(lit.lights, origin, {0, 0, 1}, 100'000), expected, 0.005 * expected);
    // A single sample is E 2 cos / (1 + cos theta_max), cos in [cos theta_max, 1] = [0.943, 1]:
    // within 3% of E (area samples are zero on the hidden half).
    Pcg32 rng(6);
    for (int i = 0; i < 1000; ++i) {
        const std::optional<LightSample> s = lit.lights.sample(origin, 0.5f, rng.next_vec2());
        ASSERT_TRUE(s);
        EXPECT_NEAR(luminance(s->Li) * s->wi.z / s->pdf, expected, 0.03 * expected);
    }
}

// A light of area A much smaller than its distance d: E = L A cos_receiver cos_light / d^2.
TEST(LightSet, SmallDistantLightGivesInverseSquareIrradiance) {
    const float size = 0.01f, radiance = 5;
    const Lit lit(scene_with({ceiling_light(size, 1, {radiance, radiance, radiance})}));
    const double expected = radiance * size * size;  // cos_receiver = cos_light = 1, d = 1
    EXPECT_NEAR(irradiance(lit.lights, origin, {0, 0, 1}, 10'000), expected, 0.01 * expected);
    // Tilting the receiver by 60 degrees halves cos_receiver.
    const Vec3 tilted{std::sqrt(3.0f) / 2, 0, 0.5f};
    EXPECT_NEAR(irradiance(lit.lights, origin, tilted, 10'000), expected / 2, 0.01 * expected / 2);
}

// E = pi L F for a Lambertian emitter, F the form factor of the 2 x 2 ceiling light one unit
// above the receiver: four 1 x 1 rectangles each with a corner straight overhead.
TEST(LightSet, LargeQuadLightIrradianceMatchesTheFormFactorOfARectangle) {
    const float radiance = 2;
    const Lit lit(scene_with({ceiling_light(2, 1, {radiance, radiance, radiance})}));
    const double expected = pi * radiance * 4 * corner_form_factor(1, 1, 1);
    EXPECT_NEAR(irradiance(lit.lights, origin, {0, 0, 1}, 200'000), expected, 0.01 * expected);
}

// Close under a 2 x 2 panel, area samples land mostly where the panel is seen at a grazing angle
// and far away; a rectangle is sampled by its solid angle instead (spherical_rectangle.h), so each
// sample counts about the same. The same square made of four triangles (a fan about its centre)
// is not a rectangle to the light and is sampled by area: both give the same irradiance, the
// rectangle with a third of the spread or less.
TEST(LightSet, RectangleSampledBySolidAngleIsLessNoisyCloseUnderIt) {
    const float radiance = 2;
    TriangleMesh fan;
    fan.positions = {{0, 0, 1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
    fan.indices = {0, 2, 1, 0, 3, 2, 0, 4, 3, 0, 1, 4};  // facing down
    const Lit rectangle(scene_with({ceiling_light(2, 1, {radiance, radiance, radiance})}));
    const Lit triangles(scene_with({object(fan, {radiance, radiance, radiance})}));
    const Vec3 ref{0.3f, -0.2f, 0.8f}, up{0, 0, 1};
    const auto spread = [&](const LightSet& lights, double& mean) {
        Pcg32 rng(12);
        double sum = 0, sum2 = 0;
        const int estimates = 400;
        for (int e = 0; e < estimates; ++e) {
            double estimate = 0;
            for (int i = 0; i < 16; ++i) {  // 16 stratified samples
                const Vec2 u{(float(i % 4) + rng.next_float()) / 4, (float(i / 4) + rng.next_float()) / 4};
                if (const std::optional<LightSample> s = lights.sample_reusing(ref, u))
                    estimate += luminance(s->Li) * std::max(0.0f, dot(s->wi, up)) / s->pdf / 16;
            }
            sum += estimate, sum2 += estimate * estimate;
        }
        mean = sum / estimates;
        return std::sqrt(std::max(0.0, sum2 / estimates - mean * mean));
    };
    double mean_rectangle = 0, mean_triangles = 0;
    const double spread_rectangle = spread(rectangle.lights, mean_rectangle);
    const double spread_triangles = spread(triangles.lights, mean_triangles);
    std::printf("irradiance %.4f / %.4f, spread of 16-sample estimates %.5f (rectangle) / %.5f (triangles)\n",
                mean_rectangle, mean_triangles, spread_rectangle, spread_triangles);
    // The panel splits into four rectangles with a corner straight above ref (0.2 below it).
    const double expected = pi * radiance *
                            (corner_form_factor(1.3, 0.8, 0.2) + corner_form_factor(1.3, 1.2, 0.2) +
                             corner_form_factor(0.7, 0.8, 0.2) + corner_form_factor(0.7, 1.2, 0.2));
    EXPECT_NEAR(mean_rectangle, expected, 0.01 * expected);
    EXPECT_NEAR(mean_triangles, expected, 4 * spread_triangles / std::sqrt(400.0));
    EXPECT_LT(spread_rectangle * 3, spread_triangles) << spread_rectangle << " vs " << spread_triangles;
}

TEST(LightSet, LightsAreChosenInProportionToTheirPower) {
    // Same size and distance, emission 1 and 3: power 1 : 3.
    const Lit lit(scene_with({ceiling_light(1, 1, {1, 1, 1}, -2), ceiling_light(1, 1, {3, 3, 3}, 2)}));
    constexpr int n = 100'000;
    Pcg32 rng(4);
    int chose_bright = 0;
    for (int i = 0; i < n; ++i) {
        const std::optional<LightSample> s = lit.lights.sample(origin, rng.next_float(), rng.next_vec2());
        ASSERT_TRUE(s.has_value());
        chose_bright += s->p.x > 0;
    }
    // Standard error sqrt(0.25 * 0.75 / n) = 0.0014: the bound is 7 of them.
    EXPECT_NEAR(double(chose_bright) / n, 0.75, 0.01);
}

// Stratified numbers for sample_reusing: the choice takes u.x, so each light gets its share of
// the strata (to one sample) and its remainder stays uniform, so the estimate stays unbiased.
TEST(LightSet, ReusingTheChoiceGivesEachLightItsShareOfStratifiedSamples) {
    const Lit lit(scene_with({ceiling_light(1, 1, {1, 1, 1}, -2), ceiling_light(1, 1, {3, 3, 3}, 2)}));
    constexpr uint32_t n = 1000;
    const Vec3 ref{0.3f, -0.2f, 0};
    int chose_bright = 0;
    double sum = 0, sum_independent = 0;
    Pcg32 rng(5);
    for (uint32_t i = 0; i < n; ++i) {
        const std::optional<LightSample> s = lit.lights.sample_reusing(ref, stratified_2d(i, n, {0.37f, 0.81f}));
        ASSERT_TRUE(s.has_value());
        chose_bright += s->p.x > 0;
        EXPECT_NEAR(lit.lights.pdf_emitter(s->p.x > 0 ? 1 : 0, ref, s->p, s->n), s->pdf, 1e-4f * s->pdf);
        sum += luminance(s->Li) * s->wi.z / s->pdf;
    }
    EXPECT_NEAR(chose_bright, 750, 1);
    for (uint32_t i = 0; i < 200 * n; ++i) {
        const std::optional<LightSample> s = lit.lights.sample(ref, rng.next_float(), rng.next_vec2());
        if (s) sum_independent += luminance(s->Li) * s->wi.z / s->pdf;
    }
    EXPECT_NEAR(sum / n, sum_independent / (200 * n), 0.01 * sum_independent / (200 * n));
}

// Choosing by importance: the near light above the receiver gets most samples, the (two-sided)
// one below its horizon only the power share; every sample's pdf is its light's pdf times the choice, so
// the estimate still agrees with the power choice's.
TEST(LightSet, ChoosingByImportanceFavoursTheLightThatCanReachThePointAndStaysUnbiased) {
    const Lit lit(scene_with({ceiling_light(0.5f, 1, {1, 1, 1}, 0.2f), ceiling_light(0.5f, 3, {1, 1, 1}, 2),
                              ceiling_light(0.5f, -1, {5, 5, 5}, -1, 0, true)}));
    constexpr uint32_t n = 20'000;
    const Vec3 ref{0.1f, 0, 0}, up{0, 0, 1};
    std::array<int, 3> chosen{};
    double sum = 0, sum_by_power = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const Vec2 u = stratified_2d(i, n, {0.37f, 0.81f});
        const std::optional<LightSample> s = lit.lights.sample_reusing(ref, up, u);
        if (s) {
            const int light = s->p.z < 0 ? 2 : s->p.z > 2 ? 1 : 0;
            ++chosen[size_t(light)];
            sum += luminance(s->Li) * std::max(0.0f, s->wi.z) / s->pdf;
        }
        const std::optional<LightSample> b = lit.lights.sample_reusing(ref, u);
        if (b) sum_by_power += luminance(b->Li) * std::max(0.0f, b->wi.z) / b->pdf;
    }
    // Power 1 : 1 : 5 x 2 sides gives the light below 10/12 by power; by importance only 0.1 * 10/12.
    EXPECT_NEAR(chosen[2], 0.1 * 10 / 12 * n, 2);
    EXPECT_GT(chosen[0], 10 * chosen[1]);
    EXPECT_NEAR(sum / n, sum_by_power / n, 0.01 * sum_by_power / n);
}

// With one light the choice is certain: choosing by importance samples it exactly as choosing by
// power does, wherever the point is and whichever way it faces (importance 0 included: behind
// the light, or the light behind the surface), to the bit.
TEST(LightSet, OneLightIsSampledAlikeChosenByImportanceOrByPower) {
    const Lit lit(scene_with({ceiling_light(0.5f, 1, {1, 1, 1}, 0.2f)}));
    Pcg32 rng(3);
    int lit_samples = 0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 ref{rng.next_float() * 4 - 2, rng.next_float() * 4 - 2, rng.next_float() * 3 - 1};
        const Vec3 n = sample_uniform_sphere(rng.next_vec2());
        const Vec2 u = rng.next_vec2();
        const std::optional<LightSample> by_importance = lit.lights.sample_reusing(ref, n, u);
        const std::optional<LightSample> by_power = lit.lights.sample_reusing(ref, u);
        ASSERT_EQ(by_importance.has_value(), by_power.has_value());
        if (!by_power) continue;
        lit_samples += !is_black(by_power->Li);
        EXPECT_EQ(by_importance->p, by_power->p);
        EXPECT_EQ(by_importance->wi, by_power->wi);
        EXPECT_EQ(by_importance->Li, by_power->Li);
        EXPECT_EQ(by_importance->pdf, by_power->pdf);
    }
    EXPECT_GT(lit_samples, 500);
}

PointLightDesc point_light(Vec3 position, Rgb intensity) {
    PointLightDesc light;
    light.position = position;
    light.intensity = intensity;
    return light;
}

TEST(LightSet, PointLightRadianceFallsOffWithTheInverseSquareOfDistance) {
    SceneDesc desc = empty_scene();
    desc.point_lights.push_back(point_light({0, 0, 2}, {8, 4, 2}));
    const Lit lit(std::move(desc));
    for (const Vec3 ref : {origin, Vec3{0, 0, -2}, Vec3{3, 0, -2}}) {
        const std::optional<LightSample> s = sample_once(lit.lights, ref);
        ASSERT_TRUE(s.has_value());
        const float d2 = length2(Vec3{0, 0, 2} - ref);
        EXPECT_TRUE(s->is_delta);
        EXPECT_EQ(s->pdf, 1.0f) << "the only light, sampled with certainty";
        EXPECT_NEAR(s->distance * s->distance, d2, 1e-5f * d2);
        EXPECT_NEAR(s->Li.r, 8 / d2, 1e-5f * 8 / d2);
        EXPECT_NEAR(s->Li.b, 2 / d2, 1e-5f * 2 / d2);
    }
}

// A spot light pointing down, full inside 25 degrees, dark beyond 30, smoothly fading between.
TEST(LightSet, SpotLightIsFullInsideItsInnerConeAndDarkOutsideItsOuterCone) {
    SceneDesc desc = empty_scene();
    PointLightDesc spot = point_light({0, 0, 1}, {1, 1, 1});
    spot.type = PointLightType::spot;
    spot.direction = {0, 0, -1};
    spot.cone_angle_deg = 30;
    spot.falloff_start_deg = 25;
    desc.point_lights.push_back(spot);
    const Lit lit(std::move(desc));
    const auto li_at_angle = [&](float degrees) {
        const Vec3 ref{std::tan(degrees * pi / 180), 0, 0};  // one unit below the spot
        const std::optional<LightSample> s = sample_once(lit.lights, ref);
        return s ? s->Li.r * length2(ref - spot.position) : 0.0f;  // intensity towards ref
    };
    EXPECT_NEAR(li_at_angle(0), 1.0f, 1e-5f);
    EXPECT_NEAR(li_at_angle(24), 1.0f, 1e-5f);
    EXPECT_GT(li_at_angle(27.5f), 0.0f);
    EXPECT_LT(li_at_angle(27.5f), 1.0f);
    EXPECT_GT(li_at_angle(26), li_at_angle(29)) << "fades towards the edge";
    EXPECT_EQ(li_at_angle(31), 0.0f);
    EXPECT_FALSE(sample_once(lit.lights, {std::tan(pi / 4), 0, 0}).has_value()) << "outside: no sample";
}

TEST(LightSet, SwitchedOffEmitterIsLeftOutUntilItIsSwitchedOn) {
    SceneDesc desc = scene_with({ceiling_light(1, 2, {})});
    desc.frame_count = 2;
    desc.fps = 1;
    desc.objects[0].emission_track = Track<Rgb>{Interpolation::step, {0, 1}, {Rgb{}, Rgb{5, 5, 5}}};
    const Lit off(desc, 0), on(desc, 1);
    EXPECT_TRUE(off.lights.empty());
    EXPECT_FALSE(off.lights.sample_emission(0.5f, {0.3f, 0.6f}, {0.2f, 0.7f}).has_value());
    EXPECT_EQ(off.lights.pdf_emitter(0, origin, {0, 0, 2}, {0, 0, -1}), 0.0f);
    const std::optional<LightSample> s = sample_once(on.lights, origin);
    ASSERT_TRUE(s.has_value());
    EXPECT_EQ(s->Li, (Rgb{5, 5, 5}));
    const std::optional<EmissionSample> e = on.lights.sample_emission(0.5f, {0.3f, 0.6f}, {0.2f, 0.7f});
    ASSERT_TRUE(e.has_value());
    EXPECT_NEAR(e->power.r, 5 * pi, 1e-4f);  // Le pi A, A = 1
}

TEST(LightSet, PointLightShinesWithTheFramesIntensity) {
    SceneDesc desc = empty_scene();
    desc.frame_count = 3;
    desc.fps = 2;
    PointLightDesc lamp = point_light({0, 0, 1}, {100, 100, 100});  // the track replaces it
    lamp.intensity_track = Track<Rgb>{Interpolation::linear, {0, 0.5f, 1}, {Rgb{2, 2, 2}, Rgb{4, 8, 0}, Rgb{}}};
    desc.point_lights.push_back(lamp);
    const Lit first(desc, 0), middle(desc, 1), last(desc, 2);
    const std::optional<LightSample> s0 = sample_once(first.lights, origin), s1 = sample_once(middle.lights, origin);
    ASSERT_TRUE(s0.has_value() && s1.has_value());
    EXPECT_EQ(s0->Li, (Rgb{2, 2, 2}));  // distance 1
    EXPECT_EQ(s1->Li, (Rgb{4, 8, 0}));
    const std::optional<EmissionSample> e = middle.lights.sample_emission(0.5f, {0.3f, 0.6f}, {0.2f, 0.7f});
    ASSERT_TRUE(e.has_value());
    EXPECT_NEAR(e->power.g, 8 * 4 * pi, 1e-3f);
    EXPECT_TRUE(last.lights.empty()) << "switched off at the last key";
}

}  // namespace
}  // namespace steadylight
