// The settings of the localized method's own steps (paper §3.3; docs/design.md): the influence
// estimate, the correction of the static records (L_t) and the blend thresholds. The photons,
// gathers and cache it shares with the photon method are in PhotonMappingSettings.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace steadylight {

constexpr int max_correction_levels = 8;

/// How L_t's correction reads the dynamic photons at a static record (record_correction.h): a
/// kernel estimate at radii radius, 2 radius, ... (levels of them), each level's detail over the
/// next coarser kept where it stands out of its own noise.
struct CorrectionSettings {
    float radius = 0.25f;     // the finest level's kernel radius, scene units
    int levels = 4;           // radius x 1, 2, 4, 8 by default
    float noise_sigmas = 3;   // a detail within this many standard errors of zero is noise: dropped
    float signal_sigmas = 5;  // beyond this many it is kept whole; in between, in proportion
    /// Estimated at records this many finest radii apart at least, taken from there by the
    /// records between (CorrectionPoints); 0: at every record.
    float point_spacing = 0.25f;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(CorrectionSettings, radius, levels, noise_sigmas, signal_sigmas,
                                                point_spacing)

struct LocalizedSettings {
    int influence_photons = 300;  // N nearest dynamic photons in the influence estimate (paper: 300)
    /// The dynamic map's estimate that corrects the static records (L_t). The paper's, 300
    /// nearest photons, changed from frame to frame far from the moving objects and flickered
    /// (docs/localized.md "A steady correction").
    CorrectionSettings correction;
    /// The influence is estimated at every n-th pixel centre in x and y (it is smooth); 0: chosen
    /// by the image's height (influence_step() in influence.h).
    int influence_step = 0;
    /// Thresholds on the influence relative to the static indirect irradiance there: below
    /// tau_lower L_t alone, above tau_upper L_y alone, smoothstep between (paper §3.3). Why these
    /// values: a density estimate of the dynamic photons from k photons has a noise of about
    /// I / sqrt(k) (the paper's k = 300): at I = 0.3 that is ~2% of the static indirect
    /// irradiance, at I = 1 ~6%, past which L_t cannot be trusted (docs/localized.md).
    float tau_lower = 0.3f;
    float tau_upper = 1.0f;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(LocalizedSettings, influence_photons, correction, influence_step,
                                                tau_lower, tau_upper)

/// Throws InputError naming `where` + "/<field>" for a value out of range, or when
/// tau_lower >= tau_upper.
void validate(const LocalizedSettings& settings, const std::string& where);

}  // namespace steadylight
