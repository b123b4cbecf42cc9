#include "steadylight/shading/bsdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "steadylight/base/rng.h"
#include "support/chi_square.h"

namespace steadylight {
namespace {

using testing::chi2_bound;
using testing::chi2_test;
using testing::direction;

constexpr Rgb white{1, 1, 1};
constexpr float cos_thetas[] = {0.05f, 0.2f, 0.5f, 0.8f, 1.0f};

Vec3 random_direction(Pcg32& rng) { return direction(1 - 2 * rng.next_float(), 2 * pi * rng.next_float()); }

float sin_theta(Vec3 w) { return std::sqrt(w.x * w.x + w.y * w.y); }

struct NamedBsdf {
    std::string name;
    std::unique_ptr<Bsdf> bsdf;
};

std::vector<NamedBsdf> white_bsdfs() {
    std::vector<NamedBsdf> all;
    all.push_back({"lambert", make_lambert(white)});
    all.push_back({"mirror", make_mirror(white)});
    for (const float roughness : {0.1f, 0.3f, 0.7f, 1.0f})
        all.push_back({"glossy " + std::to_string(roughness), make_glossy(white, roughness)});
    all.push_back({"dielectric 1.5", make_dielectric(1.5f, white)});
    all.push_back({"dielectric 1.33", make_dielectric(1.33f, white)});
    return all;
}

struct Estimate {
    double mean = 0, standard_error = 0;
};

/// Monte Carlo directional albedo E[weight] for light leaving along wo (weight zero when
/// sample() finds no direction), with its standard error. Uses the largest channel.
Estimate directional_albedo(const Bsdf& bsdf, Vec3 wo, TransportMode mode, int n, uint64_t seed) {
    Pcg32 rng(seed);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        const Vec2 u = rng.next_vec2();
        const std::optional<BsdfSample> s = bsdf.sample(wo, u, rng.next_float(), mode);
        const double w = s ? max_component(s->weight) : 0.0;
        sum += w, sum2 += w * w;
    }
    const double mean = sum / n, variance = std::max(0.0, sum2 / n - mean * mean);
    return {mean, std::sqrt(variance / n)};
}

/// Integral of pdf(wo, .) over the sphere, by the midpoint rule in (theta, phi) around the mirror
/// direction of wo with theta = pi t^2, so that cells are finest where a glossy lobe peaks.
double integrate_pdf(const Bsdf& bsdf, Vec3 wo, int n_t = 2000, int n_phi = 128) {
    const OrthonormalBasis basis = OrthonormalBasis::from_normal(Vec3{-wo.x, -wo.y, wo.z});
    const double dt = 1.0 / n_t, d_phi = 2 * pi / n_phi;
    double sum = 0;
    for (int i = 0; i < n_t; ++i) {
        const double t = (i + 0.5) * dt, theta = pi * t * t, jacobian = std::sin(theta) * 2 * pi * t;
        for (int j = 0; j < n_phi; ++j) {
            const Vec3 wi = basis.to_world(direction(float(std::cos(theta)), float((j + 0.5) * d_phi)));
            sum += bsdf.pdf(wo, wi) * jacobian;
        }
    }
    return sum * dt * d_phi;
}

/// Samples the dielectric's refraction lobe (u_lobe just below 1 picks it unless reflection is total).
BsdfSample refract(const Bsdf& dielectric, Vec3 wo, TransportMode mode) {
    const std::optional<BsdfSample> s = dielectric.sample(wo, {0.5f, 0.5f}, 0x1.fffffep-1f, mode);
    EXPECT_TRUE(s.has_value());
    return s.value_or(BsdfSample{});
}

void expect_rgb_near(Rgb actual, Rgb expected, float relative) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(actual[c], expected[c], relative * std::abs(expected[c])) << "channel " << c;
}

TEST(Bsdf, LambertWeightIsTheAlbedoOnBothSides) {
    const Rgb albedo{0.2f, 0.5f, 0.8f};
    const auto lambert = make_lambert(albedo);
    Pcg32 rng(1);
    for (const float side : {1.0f, -1.0f})
        for (int i = 0; i < 1000; ++i) {
            const Vec3 wo = direction(side * (0.01f + 0.99f * rng.next_float()), 2 * pi * rng.next_float());
            const std::optional<BsdfSample> s = lambert->sample(wo, rng.next_vec2(), 0.5f, TransportMode::radiance);
            ASSERT_TRUE(s.has_value());
            EXPECT_GT(s->wi.z * wo.z, 0.0f) << "the sample stays on the side of wo";
            expect_rgb_near(s->weight, albedo, 1e-6f);
            expect_rgb_near(lambert->eval(wo, s->wi) * (std::abs(s->wi.z) / lambert->pdf(wo, s->wi)), s->weight, 1e-5f);
        }
}

// A mirror reflects exactly its reflectance; clear glass reflects or transmits everything
// (importance transport has no 1/eta^2 factor).
TEST(Bsdf, MirrorAndClearDielectricConserveEnergyExactly) {
    const auto mirror = make_mirror({0.9f, 0.6f, 0.3f});
    const auto glass = make_dielectric(1.5f, white);
    for (const float cos_theta : cos_thetas)
        for (const float side : {1.0f, -1.0f}) {
            const Vec3 wo = direction(side * cos_theta, 0.3f);
            const std::optional<BsdfSample> s = mirror->sample(wo, {0.5f, 0.5f}, 0.5f, TransportMode::radiance);
            ASSERT_TRUE(s.has_value());
            EXPECT_EQ(s->weight, (Rgb{0.9f, 0.6f, 0.3f}));
            EXPECT_NEAR(directional_albedo(*glass, wo, TransportMode::importance, 10'000, 2).mean, 1.0, 1e-5);
        }
}

// Glass reflects with probability F and refracts with 1 - F: the lobe probabilities sum to one.
TEST(Bsdf, DielectricLobeProbabilitiesSumToOne) {
    for (const float ior : {1.5f, 1.33f}) {
        const auto glass = make_dielectric(ior, white);
        for (const float cos_theta : cos_thetas) {
            const Vec3 wo = direction(cos_theta, 1.0f);
            const auto reflected = glass->sample(wo, {0.5f, 0.5f}, 0.0f, TransportMode::importance);
            ASSERT_TRUE(reflected.has_value());
            EXPECT_NEAR(reflected->pdf, fresnel_dielectric(cos_theta, ior), 1e-6f);
            EXPECT_NEAR(reflected->pdf + refract(*glass, wo, TransportMode::importance).pdf, 1.0f, 1e-6f);
        }
    }
}

// No passive surface scatters more than it receives: E[weight] <= 1 for white BSDFs, seen
// from either side (4 standard errors of Monte Carlo slack).
TEST(Bsdf, NoBsdfReflectsMoreEnergyThanItReceives) {
    for (const NamedBsdf& b : white_bsdfs())
        for (const float cos_theta : {-1.0f, -0.5f, -0.05f, 0.05f, 0.2f, 0.5f, 0.8f, 1.0f}) {
            const Vec3 wo = direction(cos_theta, 0.7f);
            const Estimate e = directional_albedo(*b.bsdf, wo, TransportMode::importance, 20'000, 3);
            EXPECT_LE(e.mean, 1 + 4 * e.standard_error + 1e-5) << b.name << ", cos theta " << cos_theta;
            EXPECT_GT(e.mean, 0.0) << b.name << ", cos theta " << cos_theta;
        }
}

// Helmholtz reciprocity: f(wo, wi) = f(wi, wo).
TEST(Bsdf, LambertAndGlossyAreReciprocal) {
    std::vector<NamedBsdf> bsdfs;
    bsdfs.push_back({"lambert", make_lambert({0.2f, 0.5f, 0.8f})});
    for (const float roughness : {0.1f, 0.3f, 0.7f, 1.0f})
        bsdfs.push_back({"glossy " + std::to_string(roughness), make_glossy({0.3f, 0.5f, 0.9f}, roughness)});
    Pcg32 rng(4);
    for (const NamedBsdf& b : bsdfs)
        for (int i = 0; i < 2000; ++i) {
            const Vec3 wo = random_direction(rng), wi = random_direction(rng);
            const Rgb forward = b.bsdf->eval(wo, wi);
            if (wo.z * wi.z < 0) {
                EXPECT_TRUE(is_black(forward)) << b.name << ": reflection only";
            }
            expect_rgb_near(b.bsdf->eval(wi, wo), forward, 1e-5f);
        }
}

TEST(Bsdf, GlossySampleWeightIsEvalTimesCosineOverPdf) {
    Pcg32 rng(5);
    for (const float roughness : {0.1f, 0.3f, 0.7f, 1.0f}) {
        const auto glossy = make_glossy({0.3f, 0.5f, 0.9f}, roughness);
        for (int i = 0; i < 2000; ++i) {
            const Vec3 wo = random_direction(rng);
            const std::optional<BsdfSample> s = glossy->sample(wo, rng.next_vec2(), 0.5f, TransportMode::radiance);
            if (!s) continue;  // the reflected half vector pointed below the horizon
            EXPECT_GT(s->wi.z * wo.z, 0.0f);
            EXPECT_NEAR(s->pdf, glossy->pdf(wo, s->wi), 1e-4f * s->pdf);
            expect_rgb_near(s->weight, glossy->eval(wo, s->wi) * (std::abs(s->wi.z) / glossy->pdf(wo, s->wi)), 1e-4f);
        }
    }
}

// The pdf of directions is at most one: the mass it misses is that of half vectors whose mirror
// direction falls below the horizon, negligible for a sharp lobe at normal incidence. The
// quadrature is good to about 3e-4 (the pdf jumps to zero at the horizon).
TEST(Bsdf, GlossyPdfIntegratesToAtMostOne) {
    for (const float roughness : {0.1f, 0.3f, 0.7f, 1.0f}) {
        const auto glossy = make_glossy(white, roughness);
        for (const float cos_theta : cos_thetas) {
            const double integral = integrate_pdf(*glossy, direction(cos_theta, 0.4f));
            EXPECT_GE(integral, 0.5 - 1e-3) << "roughness " << roughness << ", cos theta " << cos_theta;
            EXPECT_LE(integral, 1.01) << "roughness " << roughness << ", cos theta " << cos_theta;
        }
    }
    EXPECT_GT(integrate_pdf(*make_glossy(white, 0.1f), {0, 0, 1}), 0.98);
}

// With roughness 1 (alpha = 1) the half vectors are cosine distributed, so cos^2(theta_h) is
// uniform; the mirror direction of the normal, cos(2 theta_h), falls below the horizon for half.
TEST(Bsdf, GlossyPdfOfRoughnessOneAtNormalIncidenceIntegratesToOneHalf) {
    EXPECT_NEAR(integrate_pdf(*make_glossy(white, 1.0f), {0, 0, 1}), 0.5, 1e-3);
}

TEST(Bsdf, GlossySamplesFollowTheirPdf) {
    for (const float roughness : {0.5f, 1.0f})
        for (const float cos_theta : {0.3f, 0.9f}) {
            const Vec3 wo = direction(cos_theta, 2.0f);
            const auto glossy = make_glossy(white, roughness);
            const auto sample = [&](Pcg32& rng) -> std::optional<Vec3> {
                const Vec2 u = rng.next_vec2();
                const std::optional<BsdfSample> bs = glossy->sample(wo, u, rng.next_float(), TransportMode::radiance);
                return bs ? std::optional(bs->wi) : std::nullopt;
            };
            const testing::Chi2 chi2 = chi2_test(
                sample, [&](Vec3 wi) { return glossy->pdf(wo, wi); }, -1, 16, 32, 200'000, 11);
            ASSERT_GT(chi2.dof, 30);
            EXPECT_LT(chi2.statistic, chi2_bound(chi2.dof))
                << "roughness " << roughness << ", cos theta " << cos_theta << ", dof " << chi2.dof;
        }
}

TEST(Bsdf, FresnelIsFourPercentForGlassAtNormalIncidence) {
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04f, 1e-4f);
    EXPECT_NEAR(fresnel_dielectric(-1.0f, 1.5f), 0.04f, 1e-4f) << "leaving the glass";
}

TEST(Bsdf, FresnelIsTotalBeyondTheCriticalAngleFromInside) {
    const float sin_critical = 1 / 1.5f;
    for (const float sin_i : {sin_critical + 1e-3f, 0.8f, 0.95f, 1.0f})
        EXPECT_EQ(fresnel_dielectric(-std::sqrt(1 - sin_i * sin_i), 1.5f), 1.0f) << "sin theta " << sin_i;
    EXPECT_LT(fresnel_dielectric(-std::sqrt(1 - 0.6f * 0.6f), 1.5f), 1.0f) << "just inside the critical angle";
}

// Stokes relations: a ray and its refracted partner see the same reflectance.
TEST(Bsdf, FresnelIsTheSameForBothDirectionsThroughTheBoundary) {
    for (const float cos_theta : cos_thetas) {
        const auto glass = make_dielectric(1.5f, white);
        const BsdfSample t = refract(*glass, direction(cos_theta, 0.0f), TransportMode::importance);
        EXPECT_NEAR(fresnel_dielectric(t.wi.z, 1.5f), fresnel_dielectric(cos_theta, 1.5f), 1e-5f);
    }
}

TEST(Bsdf, DielectricRefractionObeysSnellsLaw) {
    const float ior = 1.5f;
    const auto glass = make_dielectric(ior, white);
    for (const float side : {1.0f, -1.0f})
        for (const float cos_theta : {0.8f, 0.9f, 0.95f, 1.0f}) {  // all inside the critical angle
            const Vec3 wo = direction(side * cos_theta, 0.9f);
            const BsdfSample t = refract(*glass, wo, TransportMode::importance);
            EXPECT_LT(t.wi.z * wo.z, 0.0f) << "refraction crosses the boundary";
            EXPECT_NEAR(length(t.wi), 1.0f, 1e-5f);
            const float n_o = side > 0 ? 1 : ior, n_i = side > 0 ? ior : 1;
            EXPECT_NEAR(sin_theta(t.wi) * n_i, sin_theta(wo) * n_o, 1e-5f);
            EXPECT_LE(dot(Vec3{t.wi.x, t.wi.y, 0}, Vec3{wo.x, wo.y, 0}), 0.0f) << "same plane of incidence, other side";
        }
}

// Radiance entering glass is compressed into a smaller solid angle: L_t = T L / eta^2 seen from
// outside, and expands again (times eta^2) when it leaves.
TEST(Bsdf, DielectricRadianceTransmissionScalesByOneOverEtaSquared) {
    const Rgb tint{0.9f, 0.8f, 0.7f};
    const auto glass = make_dielectric(1.5f, tint);
    const Vec3 outside = direction(0.7f, 0.2f), inside = direction(-0.9f, 0.2f);
    expect_rgb_near(refract(*glass, outside, TransportMode::radiance).weight, tint / (1.5f * 1.5f), 1e-5f);
    expect_rgb_near(refract(*glass, inside, TransportMode::radiance).weight, tint * (1.5f * 1.5f), 1e-5f);
    expect_rgb_near(refract(*glass, outside, TransportMode::importance).weight, tint, 1e-6f);
}

}  // namespace
}  // namespace steadylight
