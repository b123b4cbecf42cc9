// The irradiance at a frame's photons taken from the static photons' where nothing changed
// around them (StaticIrradianceReuse), carried or estimated again where something did: the same
// values, bit for bit, whether the frame's photons were composed from the static paths or traced
// whole; and a carried value estimates the same irradiance as one estimated again.
#include "steadylight/passes/frame_photons.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "steadylight/passes/segment_pass.h"

namespace steadylight {
namespace {

struct BallPhotons {
    Scene scene{load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/ball.json")};
    RayTracer tracer{scene, scene.evaluate(0)};
    Bsdfs bsdfs = make_bsdfs(scene);
    PhotonMappingSettings settings = [] {
        PhotonMappingSettings s;
        s.photons = {.global_photons = 40'000, .caustic_photons = 0};
        return s;
    }();
    std::shared_ptr<const StaticPhotonPaths> paths =
        trace_segment_photon_paths(scene, tracer, {0, scene.frame_count() - 1}, settings);
};

/// Whether look-ups at every photon of `at` read the same bits from `a` and `b`.
void expect_same_look_ups(const IrradiancePhotons& a, const IrradiancePhotons& b, const PhotonMap& at,
                          const std::string& what) {
    const std::vector<Photon>& photons = at.photons();
    for (size_t i = 0; i < photons.size(); ++i) {
        const std::optional<Rgb> x = a.lookup(photons[i].p, photons[i].n, 0.5f);
        const std::optional<Rgb> y = b.lookup(photons[i].p, photons[i].n, 0.5f);
        ASSERT_EQ(x.has_value(), y.has_value()) << what << ", photon " << i;
        if (x) {
            ASSERT_TRUE(x->r == y->r && x->g == y->g && x->b == y->b) << what << ", photon " << i;
        }
    }
}

TEST(FramePhotons, IrradianceTakenFromTheStaticPhotonsIsTheEstimatedOne) {
    BallPhotons ball;
    for (const int frame : {30, 0}) {
        const std::string what = "ball frame " + std::to_string(frame);
        const PlacedFrame placed(ball.scene, ball.tracer, ball.bsdfs, frame);
        FrameStats stats;
        const FramePhotons composed(placed.context(), ball.settings, stats, ball.paths.get(),
                                    ball.paths->irradiance.get(), ChangedValues::searched);
        const FramePhotons traced(placed.context(), ball.settings, stats);
        ASSERT_TRUE(same_photons(composed.maps.global, traced.maps.global)) << what;
        ASSERT_EQ(composed.irradiance.size(), traced.irradiance.size()) << what;
        expect_same_look_ups(composed.irradiance, traced.irradiance, traced.maps.global, what);
        // Both ways were taken: values reused, and values estimated again where photons changed.
        EXPECT_GT(composed.irradiance.reused(), long(composed.irradiance.size()) / 20) << what;
        EXPECT_GT(composed.irradiance.computed(), 0) << what;
        EXPECT_EQ(composed.irradiance.carried(), 0) << what;
        EXPECT_EQ(traced.irradiance.reused(), 0) << what;
    }
}

TEST(FramePhotons, CarriedValuesAreTheSameComposedOrTracedWhole) {
    BallPhotons ball;
    for (const int frame : {30, 0}) {
        const std::string what = "ball frame " + std::to_string(frame);
        const PlacedFrame placed(ball.scene, ball.tracer, ball.bsdfs, frame);
        FrameStats stats;
        const IrradiancePhotons* values = ball.paths->irradiance.get();
        const FramePhotons composed(placed.context(), ball.settings, stats, ball.paths.get(), values,
                                    ChangedValues::carried);
        const FramePhotons traced(placed.context(), ball.settings, stats, ball.paths.get(), values,
                                  ChangedValues::carried, false);
        ASSERT_TRUE(same_photons(composed.maps.global, traced.maps.global)) << what;
        ASSERT_EQ(composed.static_reuse->kept.frame_ids, traced.static_reuse->kept.frame_ids) << what;
        ASSERT_EQ(composed.static_reuse->kept.added_ids, traced.static_reuse->kept.added_ids) << what;
        expect_same_look_ups(composed.irradiance, traced.irradiance, traced.maps.global, what);
        // Every way was taken, composed and traced whole alike: values reused as they are,
        // carried, and estimated again near the ball (new photons there, or so many removed
        // that the static photons' lists cannot tell, mostly), some from the lists where composed.
        for (const FramePhotons* photons : {&composed, &traced}) {
            const IrradiancePhotons& irradiance = photons->irradiance;
            EXPECT_GT(irradiance.reused(), long(irradiance.size()) / 20) << what;
            EXPECT_GT(irradiance.carried(), long(irradiance.size()) / 4) << what;
            EXPECT_GT(irradiance.computed(), 0) << what;
        }
        EXPECT_GT(composed.irradiance.from_static_lists(), 0) << what;
        EXPECT_EQ(traced.irradiance.from_static_lists(), 0) << what;
    }
}

TEST(FramePhotons, CarriedValuesEstimateTheIrradianceEstimatedAgain) {
    // A carried value is the fixed-radius estimate on the static disc over the frame's photons;
    // estimated again, it is the k-nearest one. Both are unbiased estimates of the same
    // irradiance, so over the thousands of values something changed around they agree on
    // average. Carried with a sign wrong, or a change counted off the disc, they would not: the
    // changes are a few photons of the 50 in a disc, a few percent of each value.
    BallPhotons ball;
    const PlacedFrame placed(ball.scene, ball.tracer, ball.bsdfs, 30);
    FrameStats stats;
    const FramePhotons carried(placed.context(), ball.settings, stats, ball.paths.get(), ball.paths->irradiance.get(),
                               ChangedValues::carried);
    const FramePhotons estimated(placed.context(), ball.settings, stats);
    double sum_carried = 0, sum_estimated = 0, sum_static = 0;
    long differing = 0;
    const std::vector<Photon>& photons = estimated.maps.global.photons();
    for (size_t i = 0; i < photons.size(); ++i) {
        const std::optional<Rgb> a = carried.irradiance.lookup(photons[i].p, photons[i].n, 0.5f);
        const std::optional<Rgb> b = estimated.irradiance.lookup(photons[i].p, photons[i].n, 0.5f);
        const std::optional<Rgb> s = ball.paths->irradiance->lookup(photons[i].p, photons[i].n, 0.5f);
        ASSERT_EQ(a.has_value(), b.has_value()) << "photon " << i;
        if (!a || !s || luminance(*a) == luminance(*b)) continue;
        sum_carried += luminance(*a), sum_estimated += luminance(*b), sum_static += luminance(*s);
        ++differing;
    }
    ASSERT_GT(differing, 5000);
    EXPECT_NEAR(sum_carried / sum_estimated, 1.0, 0.003) << differing << " look-ups";
    std::printf("%ld look-ups: carried / estimated again %.5f, carried / static %.5f\n", differing,
                sum_carried / sum_estimated, sum_carried / sum_static);
    // And what changed is really there: the frame's light differs from the static pass's.
    EXPECT_GT(std::abs(sum_carried / sum_static - 1.0), 0.001) << differing << " look-ups";
}

}  // namespace
}  // namespace steadylight
