// L_t's correction of the static records (record_correction.h).
#include "steadylight/passes/record_correction.h"

#include <algorithm>
#include <cmath>

#include "steadylight/base/check.h"
#include "steadylight/base/parallel.h"
#include "steadylight/photons/surface_coverage.h"

namespace steadylight {
namespace {

float level_radius(const CorrectionSettings& settings, int level) { return settings.radius * float(1 << level); }

/// How much of a detail to keep: 0 within noise_sigmas standard errors of zero, all of it beyond
/// signal_sigmas, in between the share that makes the kept detail grow linearly from 0 to whole
/// (firm shrinkage).
float kept_share(float detail, float sigma, const CorrectionSettings& settings) {
    const float z = std::abs(detail) / sigma;  // no photons: 0 / 0, dropped below
    if (!(z > settings.noise_sigmas)) return 0;
    if (z >= settings.signal_sigmas) return 1;
    return settings.signal_sigmas * (z - settings.noise_sigmas) / ((settings.signal_sigmas - settings.noise_sigmas) * z);
}

}  // namespace

const std::vector<float>& CorrectionCoverage::shares(const FrameContext& context, const IrradianceCache& cache,
                                                     const CorrectionSettings& settings) const {
    std::call_once(m_once, [&] {
        const SurfaceCoverage coverage = surface_coverage(context, Visibility::static_only);
        const std::vector<IrradianceRecord>& records = cache.records();
        const int levels = settings.levels;
        m_levels = levels;
        m_shares.resize(records.size() * size_t(levels));
        parallel_for_chunks(long(records.size()), 16, [&](long begin, long end) {
            for (long i = begin; i < end; ++i)
                for (int l = 0; l < levels; ++l) {
                    const size_t at = size_t(i) * size_t(levels) + size_t(l);
                    // A disc barely on the surface is held at 1/16, what one probe gives.
                    m_shares[at] = std::max(coverage.probes(records[size_t(i)].p, records[size_t(i)].n, level_radius(settings, l), at).share(),
                                            1.0f / 16);
                }
        });
    });
    SL_CHECK_EQ(m_levels, settings.levels);
    return m_shares;
}

Rgb correction_at(const PhotonMap& dynamic, Vec3 p, Vec3 n, const CorrectionSettings& settings, const float* shares) {
    const int levels = settings.levels;
    SL_CHECK(levels >= 1 && levels <= max_correction_levels);
    thread_local std::vector<Neighbour> found;
    dynamic.within(p, level_radius(settings, levels - 1), found);
    if (found.empty()) return {};
    // Level l's kernel: (1 - d^2 / r_l^2) 2 / (pi r_l^2 share_l) inside r_l; it integrates to 1
    // over the part of the disc on the surface.
    float inverse_r2[max_correction_levels], scale[max_correction_levels];
    for (int l = 0; l < levels; ++l) {
        const float r = level_radius(settings, l);
        inverse_r2[l] = 1 / (r * r);
        scale[l] = 2 / (pi * r * r * (shares ? shares[l] : 1.0f));
    }
    Rgb detail[max_correction_levels];
    float variance[max_correction_levels] = {};
    for (const Neighbour& neighbour : found) {
        const Photon& photon = dynamic.photons()[neighbour.index];
        if (!same_side(photon, n)) continue;
        const float y = luminance(photon.power);
        // How far off the record's tangent plane: a disc's photons lie within a quarter of its
        // radius of it (a table top's coarse discs do not read the floor under it).
        const float offset = std::abs(dot(photon.p - p, n));
        float coarser = 0;  // the next coarser level's kernel; 0 past the coarsest
        for (int l = levels - 1; l >= 0; --l) {
            const bool in_disc = offset * offset * 16 <= 1 / inverse_r2[l];
            const float kernel = in_disc ? std::max(0.0f, 1 - neighbour.distance2 * inverse_r2[l]) * scale[l] : 0.0f;
            const float weight = kernel - coarser;
            detail[l] += photon.power * weight;
            variance[l] += (y * weight) * (y * weight);
            coarser = kernel;
        }
    }
    Rgb sum;
    for (int l = 0; l < levels; ++l)
        sum += detail[l] * kept_share(luminance(detail[l]), std::sqrt(variance[l]), settings);
    return sum;
}

IrradianceCache corrected_cache(const IrradianceCache& static_cache, const PhotonMap& dynamic,
                                const CorrectionSettings& settings, const std::vector<float>& shares,
                                std::vector<uint8_t>* changed) {
    std::vector<IrradianceRecord> records = static_cache.records();
    if (changed) changed->assign(records.size(), 0);
    if (dynamic.size() > 0) {
        SL_CHECK_EQ(shares.size(), records.size() * size_t(settings.levels));
        parallel_for_chunks(long(records.size()), 64, [&](long begin, long end) {
            for (long i = begin; i < end; ++i) {
                IrradianceRecord& r = records[size_t(i)];
                const Rgb delta = correction_at(dynamic, r.p, r.n, settings, &shares[size_t(i) * size_t(settings.levels)]);
                if (delta == Rgb{}) continue;  // the record as it is, bit for bit
                const Rgb E = {std::max(0.0f, r.E.r + delta.r), std::max(0.0f, r.E.g + delta.g),
                               std::max(0.0f, r.E.b + delta.b)};
                if (changed) (*changed)[size_t(i)] = E != r.E;
                r.E = E;
            }
        });
    }
    IrradianceCache corrected(static_cache.settings());
    for (const IrradianceRecord& r : records) corrected.insert(r);
    return corrected;
}

}  // namespace steadylight
