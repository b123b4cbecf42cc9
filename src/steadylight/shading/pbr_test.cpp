// glTF's metallic-roughness BSDF (pbr.cpp): energy (white furnace), reciprocity, sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "steadylight/base/rng.h"
#include "steadylight/base/sampling.h"
#include "steadylight/shading/bsdf.h"
#include "support/bsdf_checks.h"

namespace steadylight {
namespace {

using testing::direction;

constexpr float roughnesses[] = {0.03f, 0.07f, 0.15f, 0.3f, 0.45f, 0.6f, 0.8f, 1.0f};
constexpr float cos_thetas[] = {0.05f, 0.2f, 0.5f, 0.8f, 1.0f};

PbrParams metal(Rgb base, float roughness) { return {.base = base, .metallic = 1, .roughness = roughness}; }
PbrParams plastic(Rgb base, float roughness) { return {.base = base, .metallic = 0, .roughness = roughness}; }

/// Directional albedo by stratified samples of the BSDF's own sampling (largest channel).
double albedo(const Bsdf& bsdf, Vec3 wo, int strata = 160) {
    return max_component(testing::directional_albedo(bsdf, wo, TransportMode::radiance, strata));
}

// The white furnace: a white metal and a white coated base reflect all the light that reaches
// them, at every angle and roughness, thanks to the multiple-scattering compensation.
TEST(Pbr, WhiteFurnaceHoldsWithinOnePercentAtEveryRoughness) {
    double worst = 0;
    for (const float roughness : roughnesses)
        for (const PbrParams& p : {metal({1, 1, 1}, roughness), plastic({1, 1, 1}, roughness)}) {
            const auto bsdf = make_pbr(p);
            for (const float cos_theta : cos_thetas) {
                const double e = albedo(*bsdf, direction(cos_theta, 0.3f));
                EXPECT_NEAR(e, 1.0, 0.01)
                    << (p.metallic ? "metal" : "plastic") << ", roughness " << roughness << ", cos theta " << cos_theta;
                worst = std::max(worst, std::abs(e - 1));
            }
        }
    std::printf("white furnace: largest deviation %.4f\n", worst);
}

// Without compensation a rough GGX metal loses up to ~40% at roughness 1: make sure the
// single-scattering part alone is what loses it, i.e. the test above measures something.
TEST(Pbr, CoatPartAloneReflectsLessThanTheWholeMaterial) {
    const auto bsdf = make_pbr(plastic({1, 1, 1}, 0.5f));
    const auto coat = bsdf->non_diffuse_part();
    ASSERT_TRUE(coat);
    const Vec3 wo = direction(0.5f, 0.1f);
    EXPECT_LT(albedo(*coat, wo, 64), 0.2);
}

// The cache's split: the coat's albedo plus the base's diffuse_reflectance(wo) is the whole albedo.
TEST(Pbr, CoatAlbedoPlusDiffuseReflectanceIsTheWholeAlbedo) {
    for (const float roughness : {0.2f, 0.6f})
        for (const float cos_theta : {0.1f, 0.6f, 1.0f}) {
            const Rgb base{0.6f, 0.6f, 0.6f};
            const auto bsdf = make_pbr(plastic(base, roughness));
            const Vec3 wo = direction(cos_theta, 0.3f);
            ASSERT_TRUE(bsdf->is_diffuse());
            const double whole = albedo(*bsdf, wo, 128);
            const double split =
                albedo(*bsdf->non_diffuse_part(), wo, 128) + max_component(bsdf->diffuse_reflectance(wo));
            EXPECT_NEAR(split, whole, 0.01) << "roughness " << roughness << ", cos theta " << cos_theta;
        }
}

TEST(Pbr, IsReciprocal) {
    Pcg32 rng(7);
    for (const PbrParams& p : {metal({0.9f, 0.6f, 0.3f}, 0.3f), plastic({0.2f, 0.5f, 0.8f}, 0.5f),
                               PbrParams{.base = {0.5f, 0.4f, 0.3f}, .metallic = 0.4f, .roughness = 0.8f}}) {
        const auto bsdf = make_pbr(p);
        for (int i = 0; i < 2000; ++i) {
            const Vec3 wo = direction(1 - 2 * rng.next_float(), 2 * pi * rng.next_float());
            const Vec3 wi = direction(1 - 2 * rng.next_float(), 2 * pi * rng.next_float());
            const Rgb forward = bsdf->eval(wo, wi), backward = bsdf->eval(wi, wo);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(forward[c], backward[c], 1e-5f * std::max(1.0f, forward[c]));
        }
    }
}

TEST(Pbr, SampleWeightIsEvalTimesCosineOverPdf) {
    Pcg32 rng(8);
    for (const PbrParams& p : {metal({0.9f, 0.6f, 0.3f}, 0.3f), plastic({0.2f, 0.5f, 0.8f}, 0.5f)}) {
        const auto bsdf = make_pbr(p);
        for (int i = 0; i < 2000; ++i) {
            const Vec3 wo = direction(1 - 2 * rng.next_float(), 2 * pi * rng.next_float());
            const std::optional<BsdfSample> s =
                bsdf->sample(wo, rng.next_vec2(), rng.next_float(), TransportMode::radiance);
            if (!s) continue;
            EXPECT_GT(s->wi.z * wo.z, 0.0f);
            EXPECT_NEAR(s->pdf, bsdf->pdf(wo, s->wi), 1e-3f * s->pdf);
            const Rgb expected = bsdf->eval(wo, s->wi) * (std::abs(s->wi.z) / s->pdf);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(s->weight[c], expected[c], 1e-3f * std::max(1.0f, expected[c]));
        }
    }
}

TEST(Pbr, SamplesFollowTheirPdf) {
    for (const PbrParams& p : {metal({1, 1, 1}, 0.5f), plastic({0.5f, 0.5f, 0.5f}, 0.4f)})
        for (const float cos_theta : {0.3f, 0.9f}) {
            const Vec3 wo = direction(cos_theta, 2.0f);
            const testing::Chi2 chi2 = testing::bsdf_chi2(*make_pbr(p), wo);
            ASSERT_GT(chi2.dof, 30);
            EXPECT_LT(chi2.statistic, testing::chi2_bound(chi2.dof)) << "cos theta " << cos_theta;
        }
}

// Metallic 0 without a coat (KHR_materials_specular 0) is Lambert: nothing else changes.
TEST(Pbr, UncoatedDielectricIsLambert) {
    const auto bsdf = make_pbr({.base = {0.3f, 0.6f, 0.9f}, .metallic = 0, .roughness = 0.5f, .specular = 0});
    const Vec3 wo = direction(0.5f, 0), wi = direction(0.7f, 2);
    const Rgb f = bsdf->eval(wo, wi);
    EXPECT_NEAR(f.b, 0.9f / pi, 1e-6f);
    EXPECT_FALSE(bsdf->non_diffuse_part());
}

TEST(Pbr, F0OfIor15IsFourPercent) { EXPECT_NEAR(pbr_f0(1.5f, 1), 0.04f, 1e-6f); }

}  // namespace
}  // namespace steadylight
