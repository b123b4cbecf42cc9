// Checks shared by the BSDF tests: the directional albedo by the BSDF's own sampling, and the χ²
// test of its sample() against its pdf() over the whole sphere (support/chi_square.h).
#pragma once

#include "steadylight/base/rng.h"
#include "steadylight/shading/bsdf.h"
#include "support/chi_square.h"

namespace steadylight::testing {

/// The directional albedo seen from `wo`, by strata x strata stratified samples of the BSDF's
/// own sampling (lobes chosen by a fixed random stream).
inline Rgb directional_albedo(const Bsdf& bsdf, Vec3 wo, TransportMode mode, int strata = 160) {
    Pcg32 rng(21);
    Rgb sum;
    for (int a = 0; a < strata; ++a)
        for (int b = 0; b < strata; ++b) {
            const Vec2 u{(float(a) + 0.5f) / float(strata), (float(b) + 0.5f) / float(strata)};
            const std::optional<BsdfSample> s = bsdf.sample(wo, u, rng.next_float(), mode);
            if (s) sum += s->weight;
        }
    return sum / (float(strata) * float(strata));
}

/// 200,000 samples of `bsdf` seen from `wo` (radiance), binned 16 (cos theta over [-1, 1]) x 32 (phi).
inline Chi2 bsdf_chi2(const Bsdf& bsdf, Vec3 wo) {
    const auto sample = [&](Pcg32& rng) -> std::optional<Vec3> {
        const Vec2 u = rng.next_vec2();
        const std::optional<BsdfSample> bs = bsdf.sample(wo, u, rng.next_float(), TransportMode::radiance);
        return bs ? std::optional(bs->wi) : std::nullopt;
    };
    return chi2_test(
        sample, [&](Vec3 wi) { return bsdf.pdf(wo, wi); }, -1, 16, 32, 200'000, 12);
}

}  // namespace steadylight::testing
