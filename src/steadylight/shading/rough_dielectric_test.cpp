// Rough glass (rough_dielectric.cpp): energy (white furnace), generalised reciprocity, sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "steadylight/base/rng.h"
#include "steadylight/shading/bsdf.h"
#include "steadylight/shading/microfacet.h"
#include "support/bsdf_checks.h"

namespace steadylight {
namespace {

using testing::direction;

constexpr float ior = 1.5f;
constexpr float roughnesses[] = {0.03f, 0.1f, 0.2f, 0.3f, 0.5f, 0.7f, 1.0f};
constexpr float cos_thetas[] = {0.05f, 0.2f, 0.5f, 0.8f, 1.0f};

/// Reflected plus transmitted albedo, with importance transport: energy, without radiance's
/// (eta_o / eta_i)^2 for a change of medium. 320 x 320 samples: with fewer the estimate's own
/// noise at grazing angles from inside comes near 1%.
double albedo(const Bsdf& bsdf, Vec3 wo) {
    return testing::directional_albedo(bsdf, wo, TransportMode::importance, 320).g;
}

/// The white furnace: glass that absorbs nothing sends on all the energy that reaches it,
/// reflected plus transmitted, from outside and from inside, at every roughness and angle (the
/// multiple-scattering lobe puts back what single scattering loses).
TEST(RoughDielectric, WhiteFurnaceHoldsFromBothSides) {
    for (const float roughness : roughnesses) {
        const auto bsdf = make_rough_dielectric(ior, roughness, {1, 1, 1});
        double worst = 0;
        for (const float side : {1.0f, -1.0f})
            for (const float cos_theta : cos_thetas) {
                const double error = albedo(*bsdf, direction(side * cos_theta, 0.3f)) - 1;
                EXPECT_LT(std::abs(error), 0.01) << "roughness " << roughness << ", cos theta " << side * cos_theta;
                if (std::abs(error) > std::abs(worst)) worst = error;
            }
        std::printf("rough glass, roughness %.2f: largest albedo error %+.4f\n", roughness, worst);
    }
}

// An index below 1 (a bubble of air in water) makes the outside the denser side.
TEST(RoughDielectric, WhiteFurnaceHoldsForAnIndexBelowOne) {
    const auto bsdf = make_rough_dielectric(1 / 1.33f, 0.6f, {1, 1, 1});
    for (const float cos_theta : {0.1f, 0.5f, 0.9f, -0.1f, -0.5f, -0.9f})
        EXPECT_NEAR(albedo(*bsdf, direction(cos_theta, 1.1f)), 1, 0.01) << "cos theta " << cos_theta;
}

// Radiance's generalised reciprocity (Veach 1997, eq. 5.14): f(wo, wi) / eta_o^2 = f(wi, wo) / eta_i^2,
// eta being the index on each direction's side.
TEST(RoughDielectric, IsReciprocalUpToTheSquaredIndices) {
    Pcg32 rng(7);
    for (const float roughness : {0.2f, 0.6f}) {
        const auto bsdf = make_rough_dielectric(ior, roughness, {0.9f, 0.7f, 0.5f});
        int transmissions = 0;
        for (int i = 0; i < 4000; ++i) {
            const Vec3 wo = direction(1 - 2 * rng.next_float(), 2 * pi * rng.next_float());
            const Vec3 wi = direction(1 - 2 * rng.next_float(), 2 * pi * rng.next_float());
            const auto eta = [](Vec3 w) { return w.z > 0 ? 1.0f : ior; };
            const Rgb forward = bsdf->eval(wo, wi) / (eta(wo) * eta(wo));
            const Rgb backward = bsdf->eval(wi, wo) / (eta(wi) * eta(wi));
            if (wo.z * wi.z < 0 && max_component(forward) > 0) ++transmissions;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(forward[c], backward[c], 1e-4f * std::max(1.0f, forward[c]));
        }
        EXPECT_GT(transmissions, 300);
    }
}

TEST(RoughDielectric, SampleWeightIsEvalTimesCosineOverPdf) {
    Pcg32 rng(8);
    const auto bsdf = make_rough_dielectric(ior, 0.4f, {0.9f, 0.7f, 0.5f});
    int transmissions = 0;
    for (int i = 0; i < 4000; ++i) {
        const Vec3 wo = direction(1 - 2 * rng.next_float(), 2 * pi * rng.next_float());
        const Vec2 u = rng.next_vec2();
        const float u_lobe = rng.next_float();
        const std::optional<BsdfSample> s = bsdf->sample(wo, u, u_lobe, TransportMode::radiance);
        if (!s) continue;
        EXPECT_FALSE(s->is_delta);
        EXPECT_NEAR(s->pdf, bsdf->pdf(wo, s->wi), 1e-3f * s->pdf);
        const Rgb expected = bsdf->eval(wo, s->wi) * (std::abs(s->wi.z) / s->pdf);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(s->weight[c], expected[c], 1e-3f * std::max(1.0f, expected[c]));
        // Importance differs from radiance by the squared ratio of the indices, on refraction only.
        const std::optional<BsdfSample> imp = bsdf->sample(wo, u, u_lobe, TransportMode::importance);
        ASSERT_TRUE(imp);
        const bool refracted = wo.z * s->wi.z < 0;
        transmissions += refracted;
        const float etap = !refracted ? 1 : wo.z > 0 ? ior : 1 / ior;
        EXPECT_NEAR(imp->weight.r, s->weight.r * etap * etap, 1e-3f * std::max(1.0f, imp->weight.r));
    }
    EXPECT_GT(transmissions, 1000);
}

TEST(RoughDielectric, SamplesFollowTheirPdf) {
    for (const float roughness : {0.3f, 0.7f})
        for (const float cos_theta : {0.4f, 0.9f, -0.5f, -0.9f}) {
            const Vec3 wo = direction(cos_theta, 2.0f);
            const testing::Chi2 chi2 = testing::bsdf_chi2(*make_rough_dielectric(ior, roughness, {1, 1, 1}), wo);
            ASSERT_GT(chi2.dof, 30);
            EXPECT_LT(chi2.statistic, testing::chi2_bound(chi2.dof))
                << "roughness " << roughness << ", cos theta " << cos_theta;
        }
}

// Glass below GGX's smallest roughness stays the smooth, delta dielectric it always was.
TEST(RoughDielectric, GlassBelowTheSmallestRoughnessIsSmooth) {
    MaterialDesc glass;
    glass.type = MaterialType::dielectric;
    glass.roughness = 0;
    EXPECT_TRUE(make_bsdf(glass)->is_delta());
    glass.roughness = 0.5f * min_pbr_roughness;
    EXPECT_TRUE(make_bsdf(glass)->is_delta());
    glass.roughness = 0.2f;
    const auto rough = make_bsdf(glass);
    EXPECT_FALSE(rough->is_delta());
    EXPECT_FALSE(rough->is_diffuse());
}

}  // namespace
}  // namespace steadylight
