// Two-pass photon mapping with final gathering and an irradiance cache (Jensen 2001; the paper's
// reference method, docs/design.md), every frame from scratch, composed of the passes:
//   frame photons (global and caustic maps) -> irradiance precomputed at photons (Christensen
//   1999) -> irradiance cache over the image by final gathering -> the shading pass,
//   L_r = L_d + L_i + L_c + L_s.
#pragma once

#include <optional>

#include "steadylight/base/image.h"
#include "steadylight/passes/frame_stats.h"
#include "steadylight/passes/photon_mapping_settings.h"
#include "steadylight/photons/photon_paths.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

/// The frame and its parts (AOVs). beauty = direct + indirect + caustic + specular.
struct PhotonFrame {
    Image beauty, direct, indirect, caustic, specular;
    std::optional<Image> alpha;  // with a transparent background (ShadedFrame::alpha)
    GreyImage records;           // 1 where an irradiance record projects, 0 elsewhere (paper Fig. 3)
    FrameStats stats;
};

/// With `paths` (the segment's static photon paths), the photons are composed from them rather
/// than all traced again: the same maps, so the same frame (photon_paths.h).
PhotonFrame render_photon_mapped(const FrameContext& context, const PhotonMappingSettings& settings,
                                 const StaticPhotonPaths* paths = nullptr);

}  // namespace steadylight
