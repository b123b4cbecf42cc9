// Pixel reuse (pixel_reuse.h): its conservative tests find every ray that can meet what moved,
// and a frame that reuses the static frame equals the same frame shaded whole, bit for bit,
// layer for layer, on the scenes whose camera stands still.
#include "steadylight/passes/pixel_reuse.h"

#include <algorithm>
#include <cstring>

#include <gtest/gtest.h>

#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "steadylight/passes/frame_pass.h"
#include "support/scene_builder.h"

namespace steadylight {
namespace {

const std::string source_dir = STEADYLIGHT_SOURCE_DIR;

/// A scene file of scenes/ at the test's size.
SceneDesc scene_file(const std::string& name, int width, int height) {
    SceneDesc desc = load_scene_desc(source_dir + "/scenes/" + name + ".json");
    desc.camera.width = width, desc.camera.height = height;
    return desc;
}

/// The test's own oracle: the distance from p to the segment [a, b].
float distance_to_segment(Vec3 p, Vec3 a, Vec3 b) {
    const Vec3 ab = b - a;
    const float t = std::clamp(dot(p - a, ab) / std::max(length2(ab), 1e-12f), 0.0f, 1.0f);
    return length(p - (a + ab * t));
}

Vec3 random_in_ball(Pcg32& rng, const BoundingSphere& s) {
    return s.center + sample_uniform_sphere(rng.next_vec2()) * (s.radius * std::cbrt(rng.next_float()));
}

BoundingSphere random_sphere(Pcg32& rng, float max_radius) {
    return {Vec3{rng.next_float(), rng.next_float(), rng.next_float()} * 4 - Vec3{2, 2, 2},
            rng.next_float() * max_radius};
}

TEST(BoundingSphere, SegmentsBetweenTwoSpheresThroughAThirdAreNeverMissed) {
    Pcg32 rng(7);
    int no = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const BoundingSphere from = random_sphere(rng, 0.5f), to = random_sphere(rng, 0.5f),
                             object = random_sphere(rng, 0.4f);
        const bool answer = may_meet_segments(object, from, to, 0);
        no += !answer;
        if (answer) continue;
        for (int segment = 0; segment < 64; ++segment) {
            const Vec3 a = random_in_ball(rng, from), b = random_in_ball(rng, to);
            ASSERT_GT(distance_to_segment(object.center, a, b), object.radius) << "trial " << trial;
        }
    }
    // Not an answer that is always yes: most random spheres are clear of each other's hull.
    EXPECT_GT(no, 1500);
}

// may_meet_segments answers as the hull's distance does, beyond a margin far below its callers'
// slack: spheres of every size, one inside the other, one sphere twice, and objects sized to
// come within a hair of the hull or stop a hair short of it.
TEST(BoundingSphere, SegmentsTestAnswersAsTheHullsDistance) {
    Pcg32 rng(13);
    int met = 0, missed = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const BoundingSphere from = random_sphere(rng, trial % 4 == 0 ? 3.0f : 0.5f);
        const BoundingSphere to = trial % 5 == 0 ? from : random_sphere(rng, 0.5f);
        BoundingSphere object = random_sphere(rng, 0.4f);
        // The oracle in double precision: the gap is convex in t, so a ternary search finds its
        // least value.
        const auto gap = [&](double t) {
            double distance2 = 0;
            for (int axis = 0; axis < 3; ++axis) {
                const double x = double(from.center[axis]) + (double(to.center[axis]) - from.center[axis]) * t;
                distance2 += (double(object.center[axis]) - x) * (double(object.center[axis]) - x);
            }
            return std::sqrt(distance2) - (double(from.radius) + (double(to.radius) - from.radius) * t);
        };
        double lo = 0, hi = 1;
        for (int step = 0; step < 200; ++step) {
            const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
            if (gap(a) < gap(b))
                hi = b;
            else
                lo = a;
        }
        const double least = std::min({gap(0), gap(1), gap((lo + hi) / 2)});
        if (trial % 2 == 0 && least > 1e-3) object.radius = float(least * (1 + (rng.next_float() - 0.5) * 2e-3));
        const bool answer = may_meet_segments(object, from, to, 0);
        if (least <= object.radius) {
            ASSERT_TRUE(answer) << "trial " << trial;
        } else if (least > object.radius + 1e-5) {
            ASSERT_FALSE(answer) << "trial " << trial;
        }
        answer ? ++met : ++missed;
    }
    // Both answers are given.
    EXPECT_GT(met, 3000);
    EXPECT_GT(missed, 3000);
}

// may_meet_ray's "no" is certain, and it answers as the distance does beyond its margin: rays
// from random points aimed into a sphere, at its surface (grazing) or anywhere, of any length,
// their directions not unit.
TEST(BoundingSphere, RaysThroughASphereAreNeverMissed) {
    Pcg32 rng(11);
    int met = 0, missed = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const BoundingSphere object = random_sphere(rng, 0.4f);
        const Vec3 o = Vec3{rng.next_float(), rng.next_float(), rng.next_float()} * 8 - Vec3{4, 4, 4};
        const int aim = trial % 3;
        const Vec3 target = aim == 0   ? random_in_ball(rng, object)
                            : aim == 1 ? object.center + sample_uniform_sphere(rng.next_vec2()) * object.radius
                                       : o + sample_uniform_sphere(rng.next_vec2());
        const Vec3 d = normalize(target - o) * (0.1f + 10 * rng.next_float());
        const float tmax = rng.next_float() < 0.2f ? infinity : 12 * rng.next_float() / length(d);
        // The oracle in double precision.
        const double dd = double(dot(d, d)), t = std::clamp(double(dot(object.center - o, d)) / dd, 0.0, double(tmax));
        double distance2 = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const double gap = double(o[axis]) + double(d[axis]) * t - double(object.center[axis]);
            distance2 += gap * gap;
        }
        const double distance = std::sqrt(distance2);
        const bool answer = may_meet_ray(object, o, d, tmax);
        if (distance <= object.radius) {
            ASSERT_TRUE(answer) << "trial " << trial;
        } else if (distance > object.radius + 0.01) {
            ASSERT_FALSE(answer) << "trial " << trial;
        }
        answer ? ++met : ++missed;
    }
    // Both answers are given.
    EXPECT_GT(met, 5000);
    EXPECT_GT(missed, 3000);
}

/// Whether the ray from `o` along unit `d` meets sphere `s` (the test's own oracle).
bool ray_meets(const BoundingSphere& s, Vec3 o, Vec3 d) {
    const float along = std::max(0.0f, dot(s.center - o, d));
    return length(s.center - (o + d * along)) <= s.radius;
}

TEST(PixelReuse, RaysTowardsLightsFromFarAwayThroughASphereAreNeverMissed) {
    Pcg32 rng(9);
    int no = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const BoundingSphere from = random_sphere(rng, 0.5f), object = random_sphere(rng, 0.4f);
        // Directions within a random cone, recorded as a pixel's shadow rays are.
        const Vec3 axis = sample_uniform_sphere(rng.next_vec2());
        const float cos_max = 1 - rng.next_float() * rng.next_float() * 0.5f;
        PixelTrace trace;
        std::vector<Vec3> directions;
        for (int k = 0; k < 8; ++k) {
            directions.push_back(
                OrthonormalBasis::from_normal(axis).to_world(sample_uniform_cone(rng.next_vec2(), cos_max)));
            trace.add_distant_direction(directions.back());
        }
        const bool answer = may_meet_rays(object, from, trace.to_distant_lo, trace.to_distant_hi);
        no += !answer;
        if (answer) continue;
        for (const Vec3 d : directions)
            for (int start = 0; start < 16; ++start)
                ASSERT_FALSE(ray_meets(object, random_in_ball(rng, from), d)) << "trial " << trial;
    }
    // Not an answer that is always yes.
    EXPECT_GT(no, 1000);
}

TEST(PixelReuse, ScreenMarksHoldEveryPixelWhoseRaysPassThroughTheSphere) {
    const Scene scene(scene_file("ball", 64, 48));
    const Camera camera = scene.evaluate(0).camera;
    const Vec3 eye = camera.generate_ray(0, 0).o;
    Pcg32 rng(3);
    for (int trial = 0; trial < 40; ++trial) {
        // Spheres about points the camera sees, some reaching behind it.
        const Ray through = camera.generate_ray(rng.next_float() * 64, rng.next_float() * 48);
        const BoundingSphere sphere{through.o + through.d * (rng.next_float() * 6), 0.05f + rng.next_float() * 0.6f};
        std::vector<uint8_t> mask(64 * 48, 0);
        mark_sphere_on_screen(camera, sphere, mask, trial % 2 ? Outline::round : Outline::box);
        int marked = 0;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 64; ++x) {
                marked += mask[size_t(y * 64 + x)];
                for (int k = 0; k < 12; ++k) {
                    // The pixel's corners, then points inside it.
                    const Vec2 at = k < 4 ? Vec2{float(k & 1), float(k >> 1)} : rng.next_vec2();
                    const Ray ray = camera.generate_ray(float(x) + at.x, float(y) + at.y);
                    const float t = std::max(dot(sphere.center - ray.o, ray.d), 0.0f);
                    if (length(ray.o + ray.d * t - sphere.center) <= sphere.radius) {
                        ASSERT_TRUE(mask[size_t(y * 64 + x)]) << "trial " << trial << " pixel " << x << "," << y;
                    }
                }
            }
        if (length(sphere.center - eye) > 2 * sphere.radius + 1) {
            EXPECT_LT(marked, 64 * 48 / 2) << "trial " << trial;
        }
    }
}

TEST(PixelReuse, SpheresMarkedTogetherAreThoseMarkedOneByOne) {
    const Scene scene(scene_file("ball", 97, 61));  // bands of rows that do not divide the height
    const Camera camera = scene.evaluate(0).camera;
    Pcg32 rng(5);
    std::vector<BoundingSphere> spheres{{}};  // an empty one too
    for (int i = 0; i < 80; ++i) {
        // Small and large spheres about points the camera sees.
        const Ray through = camera.generate_ray(rng.next_float() * 97, rng.next_float() * 61);
        spheres.push_back({through.o + through.d * (0.5f + rng.next_float() * 8), 0.001f + rng.next_float() * 0.1f});
    }
    for (const bool behind : {false, true}) {
        // Last, one that reaches behind the camera: every pixel.
        if (behind) spheres.push_back({camera.generate_ray(40, 30).o, 0.5f});
        std::vector<uint8_t> one_by_one(97 * 61, 0), together(97 * 61, 0);
        for (const BoundingSphere& sphere : spheres) mark_sphere_on_screen(camera, sphere, one_by_one);
        mark_spheres_on_screen(camera, spheres, together);
        EXPECT_EQ(together, one_by_one);
        const long marked = std::count(together.begin(), together.end(), 1);
        if (behind) {
            EXPECT_EQ(marked, 97 * 61);
        } else {
            // Neither a screen marked whole nor one left empty.
            EXPECT_GT(marked, 0);
            EXPECT_LT(marked, 97 * 61);
        }
    }
}

PhotonMappingSettings small_settings() {
    PhotonMappingSettings settings;
    settings.photons = {.global_photons = 40'000, .caustic_photons = 20'000};
    settings.shading.samples_per_pixel = 4;
    return settings;
}

/// A segment's static solution with its photon paths and, made at `view`, its static frame.
StaticSolution solution_with_static_frame(const Scene& scene, RayTracer& tracer, const PhotonMappingSettings& settings,
                                          int view) {
    const Segment segment{0, scene.frame_count() - 1};
    const auto paths = trace_segment_photon_paths(scene, tracer, segment, settings);
    StaticSolution solution{run_segment_pass(scene, tracer, segment, settings, paths.get())};
    solution.photon_paths = paths;
    const Bsdfs bsdfs = make_bsdfs(scene);
    const PlacedFrame placed(scene, tracer, bsdfs, view);
    solution.static_frame =
        std::make_shared<const StaticFrame>(make_static_frame(placed.context(), solution, settings, {}, 1e12).value());
    return solution;
}

/// A scene with its tracer and its segment's static solution, the static frame made at frame 0:
/// what the frame tests below start from.
struct SolvedScene {
    Scene scene;
    PhotonMappingSettings settings;
    RayTracer tracer;
    StaticSolution solution;
    Bsdfs bsdfs;

    explicit SolvedScene(SceneDesc desc, PhotonMappingSettings s = small_settings())
        : scene(std::move(desc)),
          settings(s),
          tracer(scene, scene.evaluate(0)),
          solution(solution_with_static_frame(scene, tracer, settings, 0)),
          bsdfs(make_bsdfs(scene)) {}

    /// Frame `frame` as the localized method renders it, reusing the static frame.
    LocalizedFrame render(int frame) {
        const PlacedFrame placed(scene, tracer, bsdfs, frame);
        return run_frame_pass(placed.context(), solution, settings, {}, StaticCacheUse::corrected);
    }

    /// The same frame shaded whole: without the static frame, which is then put back.
    LocalizedFrame render_whole(int frame) {
        std::shared_ptr<const StaticFrame> kept = std::move(solution.static_frame);
        LocalizedFrame whole = render(frame);
        solution.static_frame = std::move(kept);
        return whole;
    }
};

/// Every layer of two frames, bit for bit, but the one that marks the pixels redone.
void expect_same_layers(const LocalizedFrame& a, const LocalizedFrame& b, const std::string& what) {
    const auto expect_same = [&](const char* name, const auto& x, const auto& y) {
        ASSERT_EQ(x.width, y.width) << what << " " << name;
        int differing = 0;
        for (int py = 0; py < x.height; ++py)
            for (int px = 0; px < x.width; ++px) differing += !(x.at(px, py) == y.at(px, py));
        EXPECT_EQ(differing, 0) << what << " " << name;
    };
    const std::pair<const char*, Image LocalizedFrame::*> colour_layers[] = {
        {"beauty", &LocalizedFrame::beauty},     {"direct", &LocalizedFrame::direct},
        {"indirect", &LocalizedFrame::indirect}, {"caustic", &LocalizedFrame::caustic},
        {"specular", &LocalizedFrame::specular}, {"indirect_static", &LocalizedFrame::indirect_static},
        {"L_y", &LocalizedFrame::L_y},           {"L_t", &LocalizedFrame::L_t}};
    const std::pair<const char*, GreyImage LocalizedFrame::*> grey_layers[] = {
        {"influence", &LocalizedFrame::influence},
        {"dynamic", &LocalizedFrame::dynamic},
        {"static_records", &LocalizedFrame::static_records},
        {"dynamic_records", &LocalizedFrame::dynamic_records}};
    for (const auto& [name, layer] : colour_layers) expect_same(name, a.*layer, b.*layer);
    for (const auto& [name, layer] : grey_layers) expect_same(name, a.*layer, b.*layer);
    ASSERT_EQ(a.alpha.has_value(), b.alpha.has_value()) << what;
    if (a.alpha) {
        EXPECT_TRUE(a.alpha->pixels == b.alpha->pixels) << what << " alpha";
    }
}

class PixelReuseOnScene : public ::testing::TestWithParam<std::string> {};

TEST_P(PixelReuseOnScene, FramesEqualFramesShadedWhole) {
    SolvedScene solved(scene_file(GetParam(), 48, 36));
    for (const int frame : {solved.scene.frame_count() / 2, 1}) {
        const LocalizedFrame reused = solved.render(frame), whole = solved.render_whole(frame);
        const std::string what = GetParam() + " frame " + std::to_string(frame);
        expect_same_layers(reused, whole, what);
        // Reuse did something: some pixels kept their shadow rays' light or more.
        const FrameStats& r = reused.stats;
        EXPECT_GT(r.pixels_reused + r.pixels_looked_up_again + r.pixels_direct_again + r.pixels_redone_but_direct,
                  48 * 36 / 4)
            << what;
        EXPECT_EQ(r.pixels_reused + r.pixels_looked_up_again + r.pixels_direct_again + r.pixels_redone_but_direct +
                      r.pixels_redone,
                  48 * 36)
            << what;
        // Where only the corrected records change, most pixels need no ray at all; in a moving
        // object's shadow only the direct light is shaded again.
        if (GetParam() == "ball" || GetParam() == "table") {
            EXPECT_GT(r.pixels_looked_up_again + r.pixels_reused, 48 * 36 / 2) << what;
        }
        if (GetParam() == "ball" || GetParam() == "table" || GetParam() == "corridor") {
            EXPECT_GT(r.pixels_direct_again, 0) << what;
        }
        const FrameStats& w = whole.stats;
        EXPECT_EQ(w.pixels_reused + w.pixels_looked_up_again + w.pixels_direct_again + w.pixels_redone_but_direct +
                      w.pixels_redone,
                  0)
            << what;
    }
}

// The pixels whose shadow rays alone may change keep their light samples as a frame shades
// them (KeptDirectLight): the same frame shaded again sums those, asking the dynamic objects
// alone, and is still the frame shaded whole, bit for bit.
TEST_P(PixelReuseOnScene, FramesShadedAgainSumTheKeptLightSamples) {
    SolvedScene solved(scene_file(GetParam(), 48, 36));
    const int frame = solved.scene.frame_count() / 2;
    const LocalizedFrame first = solved.render(frame);
    EXPECT_EQ(first.stats.pixels_direct_from_kept, 0);
    const LocalizedFrame again = solved.render(frame), whole = solved.render_whole(frame);
    const std::string what = GetParam() + " frame " + std::to_string(frame);
    expect_same_layers(again, whole, what);
    expect_same_layers(again, first, what);
    EXPECT_EQ(again.stats.pixels_direct_again, first.stats.pixels_direct_again) << what;
    EXPECT_LE(again.stats.pixels_direct_from_kept, again.stats.pixels_direct_again) << what;
    if (GetParam() == "ball" || GetParam() == "table" || GetParam() == "corridor") {
        EXPECT_GT(again.stats.pixels_direct_from_kept, again.stats.pixels_direct_again / 2) << what;
    }
    EXPECT_LE(double(solved.solution.kept_direct_light->bytes()), KeptDirectLight::max_bytes_per_pixel * 48 * 36)
        << what;
}

INSTANTIATE_TEST_SUITE_P(Scenes, PixelReuseOnScene,
                         ::testing::Values("ball", "table", "corridor", "glass_move", "mirror_room", "blender_glass",
                                           "blender_textured", "daylit_room"),
                         [](const auto& param_info) { return param_info.param; });

// The shadow tests made a tile of pixels at a time (plan_pixels) answer as the test made pixel
// by pixel: exactly the pixels whose shadow rays may meet the ball have their direct light
// redone, in frames with the ball at either end of its path and between.
TEST(PixelReuse, ShadowTestsByTilesAnswerAsPixelByPixel) {
    SolvedScene ball(scene_file("ball", 96, 72));
    const StaticFrame& base = *ball.solution.static_frame;
    const size_t pixels = base.pixel_count();
    const int frames = ball.scene.frame_count();
    for (const int frame : {0, frames / 3, frames - 1}) {
        const PlacedFrame placed(ball.scene, ball.tracer, ball.bsdfs, frame);
        const FrameContext& context = placed.context();
        const FrameChanges changes{context.tracer.dynamic_bounds(),
                                   pixels_near_dynamic(context.frame.camera, context.tracer.dynamic_bounds()),
                                   context.lights.bounds(),
                                   std::vector<uint8_t>(pixels, 0),
                                   false,
                                   false,
                                   std::vector<uint8_t>(pixels, 0),
                                   {}};
        const PixelPlan plan = plan_pixels(context.frame.camera, base, changes);
        long shadowed = 0;
        for (size_t i = 0; i < pixels; ++i) {
            const BoundingSphere points = pixel_points(base.trace(i));
            bool may_meet = false;
            for (const BoundingSphere& object : changes.dynamic)
                for (const BoundingSphere& light : changes.lights)
                    may_meet = may_meet || may_meet_segments(object, points, light, shadow_ray_slack(points));
            ASSERT_EQ((plan.changed[i] & direct_term) != 0, may_meet) << "frame " << frame << ", pixel " << i;
            shadowed += may_meet;
        }
        // Neither none nor most: the ball's shadow is a part of the picture.
        EXPECT_GT(shadowed, 0) << "frame " << frame;
        EXPECT_LT(shadowed, long(pixels) / 2) << "frame " << frame;
    }
}

// The packing alone: every sum, look-up, the records each look-up interpolated, and albedo
// comes back bit for bit, in pixels of two tiles shaded side by side; a pixel whose camera rays
// bring more distinct albedos than KeptLookUps::max_albedos (a fine texture at many camera rays)
// keeps no look-up and is marked unkept, so that it is shaded again rather than looked up again.
TEST(StaticFrame, KeepsEverySumLookUpAndAlbedoOfAPixel) {
    FrameState frame;
    frame.camera.width = shading_tile_size + 5, frame.camera.height = 3;
    const int samples = KeptLookUps::max_albedos + 8;
    // Look-up 0 lies on record 0 (only it is used there), look-up 1 between records 1 and 2, and
    // record 3 is out of every look-up's reach.
    IrradianceCache records;
    for (const Vec3 p : {Vec3{1, 2, 0}, Vec3{1.05f, 2, 1}, Vec3{0.95f, 2, 1}, Vec3{3, 2, 1}})
        records.insert({p, {0, 0, 1}, {1, 1, 1}, 1, {}, {}});
    StaticFrame kept;
    StaticFrameMaker maker(kept, frame, samples, records, 1e9);
    const size_t few = 2, many = shading_tile_size + 1;  // in two tiles
    PixelSums sums[2];
    for (const size_t pixel : {few, many}) {
        PixelSums& s = sums[pixel == many];
        PixelSums unused;
        maker.begin(int(pixel), 0, pixel, unused);
        s.indirect = {1, 2, float(pixel)};
        s.direct = pixel == few ? s.indirect : Rgb{0.5f, -0.0f, 3};  // kept as the same, and stored
        s.specular = {0, 0, 1e-30f};
        s.extra[1] = s.indirect;
        s.extra[3] = {7, 8, 9};
        s.covered = pixel == few ? float(samples) : 3.0f;
        for (int ray = 0; ray < samples; ++ray) {
            if (ray == 5) continue;  // a ray with no look-up (it met no diffuse surface)
            const int look_up = ray % 2;
            const float albedo = pixel == few ? float(ray % 3) : float(ray);
            maker.add_look_up(pixel, ray, look_up, Vec3{1, 2, float(look_up)}, Vec3{0, 0, 1}, Rgb{albedo, 0.25f, 1});
        }
        maker.finish(pixel, s);
    }
    maker.finish_frame();
    ASSERT_TRUE(maker.fits());
    for (const size_t pixel : {few, many}) {
        const PixelSums& s = sums[pixel == many];
        const PixelSums back = kept.sums(pixel);
        const auto same = [](Rgb a, Rgb b) { return std::memcmp(&a, &b, sizeof(Rgb)) == 0; };
        EXPECT_TRUE(same(back.direct, s.direct) && same(back.indirect, s.indirect) && same(back.caustic, s.caustic) &&
                    same(back.specular, s.specular))
            << pixel;
        for (int e = 0; e < max_extra_layers; ++e) EXPECT_TRUE(same(back.extra[size_t(e)], s.extra[size_t(e)])) << e;
        EXPECT_EQ(back.covered, s.covered);
        EXPECT_TRUE(same(kept.direct(pixel), s.direct)) << pixel;
    }
    const KeptLookUps few_look_ups = kept.look_ups(few);
    EXPECT_FALSE(kept.trace(few).flags & PixelRecorder::unkept);
    for (int ray = 0; ray < samples; ++ray) {
        if (ray == 5) {
            EXPECT_EQ(few_look_ups.look_up(ray), KeptLookUps::none);
            continue;
        }
        ASSERT_EQ(few_look_ups.look_up(ray), ray % 2);
        EXPECT_EQ(few_look_ups.point(ray % 2), (Vec3{1, 2, float(ray % 2)}));
        EXPECT_EQ(few_look_ups.normal(ray % 2), (Vec3{0, 0, 1}));
        EXPECT_EQ(few_look_ups.albedo(ray), (Rgb{float(ray % 3), 0.25f, 1}));
    }
    ASSERT_EQ(few_look_ups.count(), 2);
    const auto ids = [&](int look_up) {
        std::vector<uint32_t> used;
        few_look_ups.records(look_up, used);
        return used;
    };
    EXPECT_EQ(ids(0), (std::vector<uint32_t>{0}));
    EXPECT_EQ(ids(1), (std::vector<uint32_t>{1, 2}));
    EXPECT_TRUE(kept.trace(many).flags & PixelRecorder::unkept);
    EXPECT_EQ(kept.look_ups(many).look_up(0), KeptLookUps::none);
}

// A pixel whose camera rays all look up one point under one albedo keeps one byte for them, not
// one per ray, and reads back the same.
TEST(StaticFrame, KeepsOneByteForCameraRaysThatAllLookUpAlike) {
    FrameState frame;
    frame.camera.width = 1, frame.camera.height = 1;
    const int samples = 16;
    IrradianceCache records;
    records.insert({{1, 2, 0}, {0, 0, 1}, {1, 1, 1}, 1, {}, {}});
    const auto make = [&](int rays_looking_up, StaticFrame& kept) {
        StaticFrameMaker maker(kept, frame, samples, records, 1e9);
        PixelSums sums;
        maker.begin(0, 0, 0, sums);
        for (int ray = 0; ray < rays_looking_up; ++ray)
            maker.add_look_up(0, ray, 0, Vec3{1, 2, 0}, Vec3{0, 0, 1}, Rgb{1, 2, 3});
        maker.finish(0, sums);
        maker.finish_frame();
    };
    StaticFrame alike, one_missing;
    make(samples, alike);
    make(samples - 1, one_missing);
    EXPECT_EQ(one_missing.bytes() - alike.bytes(), size_t(samples - 1));
    const KeptLookUps look_ups = alike.look_ups(0);
    for (int ray = 0; ray < samples; ++ray) {
        ASSERT_EQ(look_ups.look_up(ray), 0);
        EXPECT_EQ(look_ups.albedo(ray), (Rgb{1, 2, 3}));
    }
    EXPECT_EQ(one_missing.look_ups(0).look_up(samples - 1), KeptLookUps::none);
    std::vector<uint32_t> ids;
    look_ups.records(0, ids);
    EXPECT_EQ(ids, (std::vector<uint32_t>{0}));
}

// A tile's record sets come back as they went in, and tell whether they hold a marked record,
// also past 64 records in the tile (more than a word of bits a set).
TEST(TileRecordSets, GivesBackEverySetAndWhatItMeetsPastSixtyFourRecords) {
    Pcg32 rng(7);
    std::vector<std::vector<uint32_t>> sets = {{}, {5}};
    for (int i = 0; i < 40; ++i) {
        std::vector<uint32_t> set;
        for (uint32_t id = 0; id < 3000; id += 1 + rng.next_u32() % 200) set.push_back(id);
        sets.push_back(set);
    }
    std::vector<uint32_t> flat;
    for (const std::vector<uint32_t>& set : sets) {
        flat.push_back(uint32_t(set.size()));
        flat.insert(flat.end(), set.begin(), set.end());
    }
    const TileRecordSets packed = TileRecordSets::of(flat);
    EXPECT_GT(packed.words, 1);
    std::vector<uint32_t> back;
    for (size_t i = 0; i < sets.size(); ++i) {
        packed.get(int(i), back);
        EXPECT_EQ(back, sets[i]) << i;
    }
    // A set meets the marked records exactly when one of its ids is marked.
    std::vector<uint8_t> records(3000, 0);
    for (const uint32_t id : {5u, 1999u, 2999u}) records[id] = 1;
    const std::vector<uint8_t> marked = packed.sets_meeting(records);
    ASSERT_EQ(marked.size(), sets.size());
    int meeting = 0;
    for (size_t i = 0; i < sets.size(); ++i) {
        const bool any = std::any_of(sets[i].begin(), sets[i].end(), [&](uint32_t id) { return records[id] != 0; });
        EXPECT_EQ(marked[i] != 0, any) << i;
        meeting += any;
    }
    EXPECT_GT(meeting, 1);
    EXPECT_LT(meeting, int(sets.size()));
}

// A textured surface gives each camera ray an albedo of its own: at more camera rays than
// KeptLookUps::max_albedos, pixels on blender_textured's textures are shaded again when their
// records change, still the frame shaded whole, bit for bit.
TEST(PixelReuse, PixelsWithMoreAlbedosThanKeptAreShadedAgain) {
    PhotonMappingSettings settings = small_settings();
    settings.shading.samples_per_pixel = KeptLookUps::max_albedos + 8;
    SolvedScene textured(scene_file("blender_textured", 16, 12), settings);
    const int frame = textured.scene.frame_count() / 2;
    expect_same_layers(textured.render(frame), textured.render_whole(frame), "blender_textured");
}

// What a still camera keeps between frames, packed: a diffuse room's pixel at the default 16
// camera rays in at most 150 bytes (its trace, three sums, a look-up, an albedo and a byte per
// camera ray), against 440 when every sum and a look-up slot per camera ray were kept whole.
TEST(PixelReuse, StaticFrameKeepsADiffuseRoomsPixelInAtMost150Bytes) {
    PhotonMappingSettings settings = small_settings();
    settings.shading.samples_per_pixel = 16;
    const SolvedScene ball(scene_file("ball", 32, 24), settings);
    EXPECT_LE(double(ball.solution.static_frame->bytes()) / (32 * 24), 150);
}

// Without the analysis layers (`--layers terms`) a frame gives the same four terms and beauty,
// bit for bit, reusing a static frame that was made without them and keeps less; the analysis
// layers are left empty.
TEST(PixelReuse, FramesWithoutAnalysisLayersGiveTheSameTerms) {
    SolvedScene ball(scene_file("ball", 48, 36));
    const std::vector<int> frames = {1, ball.scene.frame_count() / 2};
    std::vector<LocalizedFrame> full;
    for (const int frame : frames) full.push_back(ball.render(frame));
    const size_t full_bytes = ball.solution.static_frame->bytes();
    {
        const PlacedFrame view(ball.scene, ball.tracer, ball.bsdfs, 0);
        ball.solution.static_frame = std::make_shared<const StaticFrame>(
            make_static_frame(view.context(), ball.solution, ball.settings, {}, 1e12, AnalysisLayers::left_out)
                .value());
    }
    EXPECT_LT(ball.solution.static_frame->bytes(), full_bytes);
    for (size_t i = 0; i < frames.size(); ++i) {
        const PlacedFrame placed(ball.scene, ball.tracer, ball.bsdfs, frames[i]);
        const LocalizedFrame terms = run_frame_pass(placed.context(), ball.solution, ball.settings, {},
                                                    StaticCacheUse::corrected, AnalysisLayers::left_out);
        EXPECT_GT(terms.stats.pixels_reused + terms.stats.pixels_looked_up_again, 48 * 36 / 2) << frames[i];
        for (Image LocalizedFrame::*layer :
             {&LocalizedFrame::beauty, &LocalizedFrame::direct, &LocalizedFrame::indirect, &LocalizedFrame::caustic,
              &LocalizedFrame::specular})
            EXPECT_TRUE((terms.*layer).pixels == (full[i].*layer).pixels) << frames[i];
        for (Image LocalizedFrame::*layer :
             {&LocalizedFrame::L_y, &LocalizedFrame::L_t, &LocalizedFrame::indirect_static})
            EXPECT_TRUE((terms.*layer).pixels.empty() && !(full[i].*layer).pixels.empty()) << frames[i];
        for (GreyImage LocalizedFrame::*layer : {&LocalizedFrame::influence, &LocalizedFrame::static_records})
            EXPECT_TRUE((terms.*layer).pixels.empty() && !(full[i].*layer).pixels.empty()) << frames[i];
    }
}

// Where the static frame would take more than its share of the memory available, frames shade
// every pixel: it is refused up front when the part every pixel takes would not fit, and
// dropped when it grows past its share while it is made.
TEST(PixelReuse, AStaticFrameThatWouldNotFitIsNotKept) {
    SolvedScene ball(scene_file("ball", 32, 24));
    const Segment segment{0, ball.scene.frame_count() - 1};
    const auto kept_with = [&](double share_bytes) {
        return segment_static_frame(ball.scene, ball.tracer, segment, ball.solution, ball.settings, {},
                                    share_bytes / static_frame_memory_share) != nullptr;
    };
    const double bytes = double(ball.solution.static_frame->bytes());
    EXPECT_TRUE(kept_with(bytes * 1.1));
    EXPECT_FALSE(kept_with(bytes * 0.9));
    EXPECT_FALSE(kept_with(32 * 24 * double(StaticFrame::fixed_bytes_per_pixel()) * 0.9));
}

TEST(PixelReuse, PixelsWithNoTermChangedAreBitIdenticalBetweenFrames) {
    SolvedScene rooms(testing::two_rooms_one_moving_ball());
    const LocalizedFrame a = rooms.render(0), b = rooms.render(1);
    int clear = 0, clear_in_b = 0;
    for (int y = 0; y < a.beauty.height; ++y)
        for (int x = 0; x < a.beauty.width; ++x) {
            clear_in_b += b.changed.at(x, y) == 0;
            if (a.changed.at(x, y) == 0 && b.changed.at(x, y) == 0) {
                ++clear;
                EXPECT_EQ(a.beauty.at(x, y), b.beauty.at(x, y)) << "pixel " << x << "," << y;
            }
        }
    // The room without the ball is reused whole.
    EXPECT_GT(clear, a.beauty.width * a.beauty.height / 3);
    EXPECT_EQ(b.stats.pixels_reused, clear_in_b);
}

// With a transparent background the static frame keeps each pixel's coverage with its sums: a
// reused pixel's alpha is the one shading gives, and stays where nothing moved. In the balls'
// world every lit surface may see the moving ball in its sky (the world's light reaches from
// everywhere), so only the background is reused there; the two rooms, lit by their lamps, are
// reused whole where the ball is not, their open sides and the space around them transparent.
TEST(PixelReuse, TransparentBackgroundKeepsAlphaWithThePixels) {
    for (SceneDesc desc : {testing::balls_before_the_world(), testing::two_rooms_one_moving_ball()}) {
        desc.camera.transparent_background = true;
        SolvedScene solved(std::move(desc));
        const Scene& scene = solved.scene;
        std::vector<LocalizedFrame> frames;
        for (const int frame : {0, 1}) {
            frames.push_back(solved.render(frame));
            expect_same_layers(frames.back(), solved.render_whole(frame),
                               scene.name() + " frame " + std::to_string(frame));
        }
        const LocalizedFrame &a = frames[0], &b = frames[1];
        ASSERT_TRUE(a.alpha && b.alpha);
        int clear = 0, empty = 0, covered = 0;
        for (int y = 0; y < a.beauty.height; ++y)
            for (int x = 0; x < a.beauty.width; ++x)
                if (a.changed.at(x, y) == 0 && b.changed.at(x, y) == 0) {
                    ++clear;
                    empty += a.alpha->at(x, y).r == 0, covered += a.alpha->at(x, y).r == 1;
                    EXPECT_EQ(a.alpha->at(x, y), b.alpha->at(x, y)) << "pixel " << x << "," << y;
                    EXPECT_EQ(a.beauty.at(x, y), b.beauty.at(x, y)) << "pixel " << x << "," << y;
                }
        EXPECT_GT(clear, a.beauty.width * a.beauty.height / 8) << scene.name();
        EXPECT_GT(empty, 0) << scene.name();
        if (!scene.desc().world) {
            EXPECT_GT(covered, a.beauty.width * a.beauty.height / 8) << scene.name();
        }
        EXPECT_GE(b.stats.pixels_reused, clear) << scene.name();
    }
}

TEST(PixelReuse, AnotherViewShadesEveryPixel) {
    SolvedScene flythrough(scene_file("flythrough", 32, 24));
    const LocalizedFrame frame = flythrough.render(flythrough.scene.frame_count() / 2);
    const FrameStats& s = frame.stats;
    EXPECT_EQ(s.pixels_reused + s.pixels_looked_up_again + s.pixels_direct_again + s.pixels_redone_but_direct +
                  s.pixels_redone,
              0);
    EXPECT_EQ(frame.changed.at(5, 5), 15.0f);  // every term computed
}

}  // namespace
}  // namespace steadylight
