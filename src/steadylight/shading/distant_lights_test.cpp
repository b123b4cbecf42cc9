// Lights from far away: a sun gives its irradiance to a surface facing it, whether exactly
// parallel or spread over a cone, and a ray into its cone sees radiance that integrates to that
// irradiance; the world gives ∫ L cos dω (π L when uniform) whatever its sampling; pdfs agree with samples;
// photons carry the light that crosses the disc covering the scene and start outside it; a
// shadow ray that leaves by a portal's rim (lifted off its wall) is weighed as through the portal.
#include <gtest/gtest.h>

#include <cmath>

#include "steadylight/base/ray.h"
#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "steadylight/scene/shapes.h"
#include "steadylight/shading/light.h"
#include "steadylight/trace/ray_tracer.h"

namespace steadylight {
namespace {

/// A 4 x 4 floor at y = 0 (the scene's bounds), lit by `suns` and `world`.
struct DistantLit {
    DistantLit(std::vector<SunLightDesc> suns, std::optional<WorldDesc> world) : scene(describe(suns, world)) {}

    static SceneDesc describe(std::vector<SunLightDesc> suns, std::optional<WorldDesc> world) {
        SceneDesc desc;
        desc.materials.push_back(MaterialDesc{});
        desc.camera.placement = {AnimatedTrs{}};
        ObjectDesc floor;
        floor.name = "floor";
        floor.geometry = make_quad({-2, 0, -2}, {0, 0, 4}, {4, 0, 0});
        floor.placement = {AnimatedTrs{}};
        desc.objects.push_back(floor);
        desc.suns = std::move(suns);
        desc.world = world;
        return desc;
    }

    Scene scene;
    FrameState frame = scene.evaluate(0);
    LightSet lights{scene, frame};
};

const Vec3 sun_travel = normalize(Vec3{1, -2, 0.5f});

SunLightDesc sun(float angle_deg) {
    return {.name = "sun", .direction = sun_travel, .irradiance = {3, 2, 1}, .angle_deg = angle_deg};
}

/// Irradiance at the origin on a surface of normal `n` from next-event samples, luminance.
double irradiance(const LightSet& lights, Vec3 n, int samples, bool with_normal) {
    Pcg32 rng(3);
    double sum = 0;
    for (int i = 0; i < samples; ++i) {
        const std::optional<LightSample> s =
            lights.sample({0, 0, 0}, rng.next_float(), rng.next_vec2(), with_normal ? n : Vec3{});
        if (!s) continue;
        EXPECT_TRUE(std::isinf(s->distance));
        sum += luminance(s->Li) * std::max(0.0f, dot(s->wi, n)) / s->pdf;
    }
    return sum / samples;
}

TEST(DistantLights, ASunGivesItsIrradianceToASurfaceFacingIt) {
    for (const float angle : {0.0f, 0.53f, 10.0f}) {
        const DistantLit lit({sun(angle)}, std::nullopt);
        const double E = irradiance(lit.lights, -sun_travel, 20000, true);
        EXPECT_NEAR(E, luminance({3, 2, 1}), 0.01 * luminance({3, 2, 1})) << angle << " degrees";
        // Tilted by 60 degrees: a cosine of a half.
        const Vec3 tilted =
            OrthonormalBasis::from_normal(-sun_travel).to_world({std::sin(pi / 3), 0, std::cos(pi / 3)});
        EXPECT_NEAR(irradiance(lit.lights, tilted, 20000, true), 0.5 * luminance({3, 2, 1}),
                    0.01 * luminance({3, 2, 1}))
            << angle << " degrees";
    }
}

TEST(DistantLights, ARayIntoTheSunsConeSeesRadianceThatAddsUpToItsIrradiance) {
    const DistantLit lit({sun(4.0f)}, std::nullopt);
    // ∫ L(w) cos dω over the sphere, with uniform directions in a cone a little wider than the sun's.
    const float cos_wide = std::cos(3.0f * pi / 180);
    const OrthonormalBasis basis = OrthonormalBasis::from_normal(-sun_travel);
    Pcg32 rng(5);
    double sum = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const Vec3 local = sample_uniform_cone(rng.next_vec2(), cos_wide);
        sum += luminance(lit.lights.escaped_radiance(basis.to_world(local))) * local.z / uniform_cone_pdf(cos_wide);
    }
    EXPECT_NEAR(sum / n, luminance({3, 2, 1}), 0.01 * luminance({3, 2, 1}));
    EXPECT_TRUE(is_black(lit.lights.escaped_radiance(sun_travel)));  // away from the sun: nothing
    // Exactly parallel light cannot be seen, only sampled.
    const DistantLit hard({sun(0)}, std::nullopt);
    EXPECT_TRUE(is_black(hard.lights.escaped_radiance(-sun_travel)));
}

TEST(DistantLights, TheWorldGivesPiTimesItsRadianceWithOrWithoutANormal) {
    const DistantLit lit({}, WorldDesc::uniform(Rgb{0.5f, 1, 2} * 2));
    const double expected = pi * luminance({1, 2, 4});
    for (const Vec3 n : {Vec3{0, 1, 0}, normalize(Vec3{1, 1, 1})})
        for (const bool with_normal : {true, false})
            EXPECT_NEAR(irradiance(lit.lights, n, 200000, with_normal), expected, 0.01 * expected) << with_normal;
    EXPECT_EQ(luminance(lit.lights.escaped_radiance(normalize(Vec3{0.3f, -1, 0.2f}))), luminance({1, 2, 4}));
}

/// A world image: a dim blue sky over a darker ground, with a small bright sun 40 degrees up.
WorldDesc image_world() {
    Image image(64, 32);
    for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 64; ++i) image.at(i, j) = j < 16 ? Rgb{0.2f, 0.3f, 0.6f} : Rgb{0.1f, 0.08f, 0.05f};
    image.at(40, 7) = Rgb{4000, 3800, 3500};
    return {.radiance = std::make_shared<EnvironmentMap>(std::move(image), 1.5f, 20.0f), .description = "test"};
}

/// ∫ L(w) max(0, w·n) dω over the sphere by a fine grid in (θ, φ), luminance.
double integrated_irradiance(const EnvironmentMap& map, Vec3 n) {
    const int rows = 2048, columns = 4096;
    double sum = 0;
    for (int j = 0; j < rows; ++j) {
        const double theta = pi * (j + 0.5) / rows;
        for (int i = 0; i < columns; ++i) {
            const double phi = 2 * pi * (i + 0.5) / columns;
            const Vec3 w{float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                         float(std::sin(theta) * std::sin(phi))};
            sum += luminance(map.radiance(w)) * std::max(0.0f, dot(w, n)) * std::sin(theta);
        }
    }
    return sum * (pi / rows) * (2 * pi / columns);
}

// An image with a small bright sun: next-event samples, with or without the normal, give the
// irradiance the image's radiance integrates to, and escaped rays see the image.
TEST(DistantLights, AnImageWorldGivesTheIrradianceItsRadianceIntegratesTo) {
    const WorldDesc world = image_world();
    const DistantLit lit({}, world);
    for (const Vec3 n : {Vec3{0, 1, 0}, normalize(Vec3{1, 1, 1}), normalize(Vec3{-1, 0.2f, 0})}) {
        const double expected = integrated_irradiance(*world.radiance, n);
        for (const bool with_normal : {true, false})
            EXPECT_NEAR(irradiance(lit.lights, n, 400000, with_normal), expected, 0.015 * expected)
                << n.x << " " << n.y << " " << n.z << " " << with_normal;
    }
    const Vec3 w = normalize(Vec3{0.3f, -1, 0.2f});
    EXPECT_EQ(lit.lights.escaped_radiance(w), world.radiance->radiance(w));
}

// Photons of an image world carry, on average, its mean radiance over the sphere times 4π and
// the disc's area, and leave in directions the image sends light from.
TEST(DistantLights, PhotonsOfAnImageWorldCarryItsMeanRadiance) {
    const WorldDesc world = image_world();
    const DistantLit lit({}, world);
    const BoundingSphere& bounds = lit.scene.bounds();
    Pcg32 rng(5);
    double power = 0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
        const std::optional<EmissionSample> e =
            lit.lights.sample_emission(rng.next_float(), rng.next_vec2(), rng.next_vec2());
        ASSERT_TRUE(e);
        power += luminance(e->power);
        EXPECT_GT(length(e->p - bounds.center), bounds.radius);
    }
    const double expected = world.radiance->mean_luminance() * 4 * pi * pi * bounds.radius * bounds.radius;
    EXPECT_NEAR(power / n, expected, 0.01 * expected);
}

// Without portals, photons of the world are aimed at the openings the camera looks out of:
// their directions half of the time, their starts three times in four. Through any region they
// carry the light that crosses it: L Ω π r² into a sphere of radius r from a cone of solid angle
// Ω, whether the cone's directions or the sphere were aimed at or not.
TEST(DistantLights, PhotonsOfTheWorldAimedAtOpeningsCarryTheLightThatCrossesAnyRegion) {
    const WorldDesc world = WorldDesc::uniform({1, 1, 1});
    Scene scene(DistantLit::describe({}, world));
    const Vec3 opening{1.5f, 0.5f, 0}, elsewhere{-1.5f, 0.5f, 0.5f};
    // Rays from inside leave through the opening upwards, in a cone about a diagonal (where the
    // octahedral map's bins are smallest by solid angle).
    const Vec3 out_axis = normalize(Vec3{1, 1.1f, 0.7f});
    std::vector<std::pair<Vec3, Vec3>> crossings;
    Pcg32 marks(2);
    for (int i = 0; i < 4000; ++i) {
        const Vec3 out = normalize(Vec3{1, 0.8f + 0.6f * marks.next_float(), 0.4f + 0.6f * marks.next_float()});
        crossings.emplace_back(-out,
                               opening + Vec3{0, 0.2f * marks.next_float() - 0.1f, 0.2f * marks.next_float() - 0.1f});
    }
    scene.set_distant_photon_targets(std::make_shared<const DistantPhotonTargets>(scene.bounds(), crossings));
    const FrameState frame = scene.evaluate(0);
    const LightSet aimed(scene, frame);
    const DistantLit spread({}, world);

    // The power of photons crossing the sphere about `centre` (radius `radius`) that come from
    // within `cos_cone` of out_axis, over the sphere's cross-section, and how many.
    const auto through = [&](const LightSet& lights, Vec3 centre, float radius, float cos_cone) {
        Pcg32 rng(9);
        double power = 0;
        int count = 0;
        const int n = 1000000;
        for (int i = 0; i < n; ++i) {
            const std::optional<EmissionSample> e =
                lights.sample_emission(rng.next_float(), rng.next_vec2(), rng.next_vec2());
            if (!e || dot(-e->d, out_axis) < cos_cone) continue;
            const Vec3 to_centre = centre - e->p;
            if (length(to_centre - e->d * dot(to_centre, e->d)) > radius) continue;
            power += luminance(e->power);
            ++count;
        }
        return std::pair{power / n / (pi * radius * radius), count};
    };
    // The sphere aimed at gets 20,000 photons from the cone (a cone inside the directions
    // aimed at), the other one (larger, as only a quarter of the photons start anywhere) about
    // 200: 3% and 10% are about three standard deviations.
    const float cos_cone = std::cos(5 * pi / 180);
    const double cone = 2 * pi * (1 - cos_cone), all = 4 * pi;
    const auto [aimed_power, aimed_count] = through(aimed, opening, 0.3f, cos_cone);
    EXPECT_NEAR(aimed_power, cone, 0.03 * cone);
    EXPECT_GT(aimed_count, 20 * through(spread.lights, opening, 0.3f, cos_cone).second);
    EXPECT_NEAR(through(aimed, elsewhere, 0.8f, cos_cone).first, cone, 0.10 * cone);
    EXPECT_NEAR(through(aimed, opening, 0.3f, -1).first, all, 0.03 * all);
    EXPECT_NEAR(through(aimed, elsewhere, 0.8f, -1).first, all, 0.03 * all);
}

/// A window: 2 x 1 in the plane x = 1, facing -x (into the room at x < 1), y in [0.5, 1.5].
const PortalDesc window{.corner = {1, 0.5f, -1}, .edge_u = {0, 0, 2}, .edge_v = {0, 1, 0}};

/// Irradiance at `ref` (normal `n`) from the directions that pass through `window`, from
/// next-event samples of `lights`, and their relative variance per sample.
std::pair<double, double> irradiance_through_window(const LightSet& lights, Vec3 ref, Vec3 n, int samples) {
    Pcg32 rng(11);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < samples; ++i) {
        const std::optional<LightSample> s = lights.sample(ref, rng.next_float(), rng.next_vec2(), n);
        if (!s) continue;
        const Vec3 q = ref + s->wi * ((window.corner.x - ref.x) / s->wi.x);
        const bool through = s->wi.x > 0 && q.y >= 0.5f && q.y <= 1.5f && q.z >= -1 && q.z <= 1;
        const double value = through ? luminance(s->Li) * std::max(0.0f, dot(s->wi, n)) / s->pdf : 0;
        sum += value, sum2 += value * value;
    }
    const double mean = sum / samples;
    return {mean, (sum2 / samples - mean * mean) / (mean * mean)};
}

// The world's direct light through a window: with the window as a portal, samples give the
// same irradiance (the integral of the image through the window, by a fine grid), with a
// fraction of the variance; the irradiance from every direction is unchanged.
TEST(DistantLights, PortalsSampleTheWorldThroughTheWindowWithoutBias) {
    const WorldDesc world = image_world();
    const Vec3 ref{0, 1, 0.2f}, n = normalize(Vec3{1, 0.2f, 0});
    // The grid integral restricted to the window.
    double expected = 0;
    const int rows = 1024, columns = 2048;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            const float u = (float(i) + 0.5f) / float(columns), v = (float(j) + 0.5f) / float(rows);
            const Vec3 q{1, 0.5f + v, -1 + 2 * u};
            const Vec3 d = q - ref;
            const float r2 = length2(d);
            const Vec3 w = d / std::sqrt(r2);
            // dω = dA cos_window / r², cos_window = w.x.
            expected += luminance(world.radiance->radiance(w)) * std::max(0.0f, dot(w, n)) * w.x / r2 *
                        (2.0 / (rows * columns));
        }
    SceneDesc with = DistantLit::describe({}, world);
    with.portals = {window};
    const Scene portal_scene(with);
    const LightSet portal_lights(portal_scene, portal_scene.evaluate(0));
    const DistantLit plain({}, world);
    const auto [through_portal, variance_portal] = irradiance_through_window(portal_lights, ref, n, 200000);
    const auto [through_plain, variance_plain] = irradiance_through_window(plain.lights, ref, n, 200000);
    EXPECT_NEAR(through_portal, expected, 0.01 * expected);
    EXPECT_NEAR(through_plain, expected, 0.03 * expected);
    EXPECT_LT(variance_portal, 0.25 * variance_plain) << variance_portal << " " << variance_plain;
    EXPECT_NEAR(irradiance(portal_lights, n, 200000, true), integrated_irradiance(*world.radiance, n),
                0.02 * integrated_irradiance(*world.radiance, n));
}

// Photons through portals carry what enters by the window: a sun's irradiance times the
// window's area facing it; a uniform world's π L A. Each starts outside the scene and passes
// through the window.
TEST(DistantLights, PhotonsThroughPortalsCarryTheLightThatEntersByThem) {
    const Vec3 travel = normalize(Vec3{-1, -0.5f, 0.3f});
    for (const bool world : {false, true}) {
        SceneDesc desc = DistantLit::describe(world ? std::vector<SunLightDesc>{}
                                                    : std::vector<SunLightDesc>{{.name = "sun",
                                                                                 .direction = travel,
                                                                                 .irradiance = {3, 2, 1},
                                                                                 .angle_deg = 0}},
                                              world ? std::optional(WorldDesc::uniform({1, 1, 1})) : std::nullopt);
        desc.portals = {window};  // photons enter along -x
        ASSERT_LT(desc.portals[0].inward_normal().x, -0.99f);
        const Scene scene(desc);
        const LightSet lights(scene, scene.evaluate(0));
        Pcg32 rng(6);
        double power = 0;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            const std::optional<EmissionSample> e =
                lights.sample_emission(rng.next_float(), rng.next_vec2(), rng.next_vec2());
            ASSERT_TRUE(e);
            EXPECT_TRUE(e->from_far_away);
            if (is_black(e->power)) continue;
            power += luminance(e->power);
            EXPECT_GT(length(e->p - scene.bounds().center), scene.bounds().radius);
            const Vec3 q = e->p + e->d * ((1 - e->p.x) / e->d.x);
            EXPECT_TRUE(q.y >= 0.5f - 1e-4f && q.y <= 1.5f + 1e-4f && q.z >= -1 - 1e-4f && q.z <= 1 + 1e-4f)
                << q.x << " " << q.y << " " << q.z;
        }
        const double expected = world ? pi * 2 : luminance({3, 2, 1}) * 2 * std::max(0.0f, -travel.x);
        EXPECT_NEAR(power / n, expected, (world ? 0.01 : 1e-4) * expected) << world;
    }
}

// Shadow rays start lifted off their surface (spawn_ray()), so from daylit_room's back wall one
// can leave by the window where the line from the point meets the wall beside the window. Every
// direction the tracer lets out by the window's rim is weighed with the portal's density, as
// one through its middle: one weighed by the other strategies' density alone would count about a
// hundred times too much and light its pixel as a bright speck.
TEST(DistantLights, DirectionsOutByAPortalsRimAreWeighedAsThroughItsMiddle) {
    SceneDesc desc = load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/daylit_room.json");
    desc.suns.clear();  // the world alone
    const Scene scene(desc);
    const FrameState frame = scene.evaluate(0);
    const RayTracer tracer(scene, frame);
    const LightSet lights(scene, frame);
    const PortalDesc& portal = scene.desc().portals.at(0);
    ASSERT_LT(portal.inward_normal().x, -0.99f);  // the window in the wall x = 5.5
    // The light's density for w at ref, from the power heuristic's weight against a density of 1.
    const auto light_pdf = [&](Vec3 ref, Vec3 w, Vec3 n) {
        return std::sqrt(luminance(lights.escaped_radiance(w)) / luminance(lights.escaped_radiance(ref, w, n, 1)) - 1);
    };
    const Vec3 n{0, 0, -1};  // the back wall's, at z = 5.5
    Pcg32 rng(4);
    int out = 0, out_where_the_line_meets_the_wall = 0;
    for (int i = 0; i < 4000; ++i) {
        const Vec3 p{0.5f + 4.5f * rng.next_float(), 0.3f + 4.9f * rng.next_float(), 5.5f};
        // Aimed from the lifted start at a point of the window's rim, give or take 2 mm.
        const float a = rng.next_float(), hair = (rng.next_float() - 0.5f) * 4e-3f;
        const int edge = int(rng.next_u32() % 4);
        const Vec3 along = edge < 2 ? portal.edge_u : portal.edge_v, across = edge < 2 ? portal.edge_v : portal.edge_u;
        const Vec3 rim =
            portal.corner + along * a + across * float(edge % 2) + normalize(across) * (edge % 2 ? hair : -hair);
        const Ray shadow = spawn_ray(p, n, normalize(rim - spawn_ray(p, n, n).o));
        if (tracer.occluded(shadow)) continue;
        ++out;
        const Vec3 through_line = p + shadow.d * ((5.5f - p.x) / shadow.d.x);
        const Vec3 q = through_line - portal.corner;
        const float s = dot(q, portal.edge_u) / length2(portal.edge_u),
                    t = dot(q, portal.edge_v) / length2(portal.edge_v);
        out_where_the_line_meets_the_wall += s < 0 || s > 1 || t < 0 || t > 1;
        const Vec3 middle = normalize(portal.corner + (portal.edge_u + portal.edge_v) * 0.5f - p);
        ASSERT_GT(light_pdf(p, shadow.d, n), 0.5f * light_pdf(p, middle, n))
            << "from " << p.x << " " << p.y << " " << p.z << " out at " << s << " " << t;
    }
    // The test meets the case: rays out by the window whose line from the point meets the wall.
    EXPECT_GT(out, 1000);
    EXPECT_GT(out_where_the_line_meets_the_wall, 50);
}

TEST(DistantLights, SampledDirectionsAreWeighedAsEscapedRaysAre) {
    // Light sampling and a BSDF-sampled ray that escapes weigh each light by the same pdfs: a
    // direction with a BSDF pdf equal to its light pdf gets half of the light's radiance.
    const Vec3 n = normalize(Vec3{0.2f, 1, -0.1f});
    for (const int world : {0, 1, 2}) {
        const DistantLit lit(world ? std::vector<SunLightDesc>{} : std::vector{sun(2.0f)},
                             world == 1   ? std::optional(WorldDesc::uniform({1, 1, 1}))
                             : world == 2 ? std::optional(image_world())
                                          : std::nullopt);
        Pcg32 rng(8);
        for (int i = 0; i < 200; ++i) {
            const std::optional<LightSample> s = lit.lights.sample({0, 0, 0}, rng.next_float(), rng.next_vec2(), n);
            ASSERT_TRUE(s);
            EXPECT_NEAR(luminance(lit.lights.escaped_radiance({0, 0, 0}, s->wi, n, s->pdf)), 0.5f * luminance(s->Li),
                        1e-3f * luminance(s->Li));
        }
    }
}

TEST(DistantLights, PhotonsCarryTheLightThatCrossesTheDiscCoveringTheScene) {
    const DistantLit lit({sun(0.53f)}, std::nullopt);
    const BoundingSphere& bounds = lit.scene.bounds();
    ASSERT_NEAR(bounds.radius, std::sqrt(8.0f), 1e-4f);
    Pcg32 rng(4);
    double power = 0;
    const int n = 5000;
    for (int i = 0; i < n; ++i) {
        const std::optional<EmissionSample> e =
            lit.lights.sample_emission(rng.next_float(), rng.next_vec2(), rng.next_vec2());
        ASSERT_TRUE(e);
        power += luminance(e->power);
        // From outside the scene's sphere, towards it, passing within its radius of the centre.
        EXPECT_GT(length(e->p - bounds.center), bounds.radius);
        EXPECT_LT(dot(e->d, sun_travel), 1.0001f);
        EXPECT_GT(dot(e->d, sun_travel), std::cos(0.53f * pi / 360) - 1e-5f);
        const Vec3 to_centre = bounds.center - e->p;
        EXPECT_LE(length(to_centre - e->d * dot(to_centre, e->d)), bounds.radius * 1.001f);
    }
    EXPECT_NEAR(power / n, luminance({3, 2, 1}) * pi * bounds.radius * bounds.radius, 1e-3 * power / n);
}

}  // namespace
}  // namespace steadylight
