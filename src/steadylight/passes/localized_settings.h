// The settings of the localized method's own steps (paper §3.3; DESIGN.md §2.2): the influence
// estimate, the correction of the static records (L_t) and the blend thresholds. The photons,
// gathers and cache it shares with the photon method are in PhotonMappingSettings.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "steadylight/photons/photon_map.h"

namespace steadylight {

struct LocalizedSettings {
    int influence_photons = 300;  // N nearest dynamic photons in the influence estimate (paper: 300)
    /// The dynamic map's estimate that corrects the static records (L_t). Many photons: a noisy
    /// correction changes from frame to frame and flickers (k = 50 flickered more than the
    /// photon method on TABLE; 300 flickers 25% less than it).
    DensitySettings correction_estimate{.k = 300, .max_radius = 0.5f};
    int influence_step = 4;       // influence estimated at every n-th pixel centre in x and y (it is smooth)
    /// Thresholds on the influence relative to the static indirect irradiance there: below
    /// tau_lower L_t alone, above tau_upper L_y alone, smoothstep between (paper §3.3). Why these
    /// values: L_t's correction is a density estimate of the dynamic photons, whose noise is about
    /// I / sqrt(k) for k photons (k = 300): at I = 0.3 that is ~2% of the static indirect
    /// irradiance, at I = 1 ~6%, past which L_t cannot be trusted (docs/localized.md).
    float tau_lower = 0.3f;
    float tau_upper = 1.0f;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(LocalizedSettings, influence_photons, correction_estimate,
                                                influence_step, tau_lower, tau_upper)

/// Throws InputError naming `where` + "/<field>" for a value out of range, or when
/// tau_lower >= tau_upper.
void validate(const LocalizedSettings& settings, const std::string& where);

}  // namespace steadylight
