// The settings of the photon-mapping passes, shared by every method built on them (photon,
// localized, frozen): photons per frame and segment, the irradiance precomputed at photons
// (Christensen 1999), final gathering, the irradiance cache and the shading pass. One copy for
// all of them: the localized method's segment and frame passes read the same photons and
// gathers as the photon method (the paper compares them at equal settings, its §5).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "steadylight/irradiance/final_gather.h"
#include "steadylight/irradiance/irradiance_cache.h"
#include "steadylight/passes/shading_pass.h"
#include "steadylight/photons/photon_tracer.h"

namespace steadylight {

struct PhotonMappingSettings {
    PhotonSettings photons;
    DensitySettings irradiance_estimate{.k = 50, .max_radius = 0.5f};  // at the precomputed photons
    int irradiance_stride = 4;  // precompute irradiance at one in n global photons (by their hash)
    GatherSettings gather;
    CacheSettings cache;
    ShadingSettings shading;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PhotonMappingSettings, photons, irradiance_estimate, irradiance_stride,
                                                gather, cache, shading)

/// Throws InputError naming `where` + "/<field>/..." for a value out of range.
void validate(const PhotonMappingSettings& settings, const std::string& where);

}  // namespace steadylight
