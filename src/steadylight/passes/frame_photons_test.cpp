// The irradiance at a frame's photons taken from the static photons' where nothing changed
// around them (StaticIrradianceReuse), or estimated from the static photons' lists of
// neighbours where something did, against the same values estimated again over maps traced
// whole: bit for bit.
#include "steadylight/passes/frame_photons.h"

#include <gtest/gtest.h>

#include "steadylight/passes/segment_pass.h"

namespace steadylight {
namespace {

TEST(FramePhotons, IrradianceTakenFromTheStaticPhotonsIsTheEstimatedOne) {
    const Scene scene(load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/ball.json"));
    RayTracer tracer(scene, scene.evaluate(0));
    PhotonMappingSettings settings;
    settings.photons = {.global_photons = 40'000, .caustic_photons = 0};
    const auto paths = trace_segment_photon_paths(scene, tracer, {0, scene.frame_count() - 1}, settings);
    const Bsdfs bsdfs = make_bsdfs(scene);
    for (const int frame : {30, 0}) {
        const std::string what = "ball frame " + std::to_string(frame);
        const PlacedFrame placed(scene, tracer, bsdfs, frame);
        FrameStats stats;
        const FramePhotons composed(placed.context(), settings, stats, paths.get(), paths->irradiance.get(),
                                    ChangedValues::from_static_lists);
        const FramePhotons traced(placed.context(), settings, stats);
        ASSERT_TRUE(same_photons(composed.maps.global, traced.maps.global)) << what;
        ASSERT_EQ(composed.irradiance.size(), traced.irradiance.size()) << what;
        // Look-ups at every photon: each reads its nearest carrier's value.
        const std::vector<Photon>& photons = traced.maps.global.photons();
        for (size_t i = 0; i < photons.size(); ++i) {
            const std::optional<Rgb> a = composed.irradiance.lookup(photons[i].p, photons[i].n, 0.5f);
            const std::optional<Rgb> b = traced.irradiance.lookup(photons[i].p, photons[i].n, 0.5f);
            ASSERT_EQ(a.has_value(), b.has_value()) << what << ", photon " << i;
            if (a) {
                ASSERT_TRUE(a->r == b->r && a->g == b->g && a->b == b->b) << what << ", photon " << i;
            }
        }
        // Every way was taken: values reused, and values estimated again where photons changed,
        // most of them from the static photons' lists of neighbours.
        EXPECT_GT(composed.irradiance.reused(), long(composed.irradiance.size()) / 20) << what;
        EXPECT_GT(composed.irradiance.computed(), 0) << what;
        if (frame != 0) {
            EXPECT_GT(composed.irradiance.from_static_lists(), composed.irradiance.computed() / 2) << what;
        }
        EXPECT_EQ(traced.irradiance.reused(), 0) << what;
    }
}

}  // namespace
}  // namespace steadylight
