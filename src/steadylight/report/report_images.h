// The image sections of `steadylight report`: the contact sheet (every frame's PNG, embedded
// byte for byte as a data URI) and the AOVs of one frame (each RGB layer of its EXR, encoded with
// the same clamp-and-sRGB view as the frame PNGs and embedded).
#pragma once

#include <optional>
#include <string>

#include "steadylight/report/frame_catalog.h"

namespace steadylight {

/// Per scene a grid of `<figure class="frame" data-frame="N">` thumbnails with their method and
/// time. Throws InputError naming a PNG that cannot be read.
std::string build_contact_sheet_html(const FrameCatalog& catalog);

/// The frame whose AOVs a scene shows: `requested` when the scene has it, else the middle one
/// of its frames that have an EXR; std::nullopt when there is none.
std::optional<int> choose_aov_frame(const std::vector<CatalogFrame>& frames, std::optional<int> requested);

/// Per scene the layers of the chosen frame (see choose_aov_frame) as `<figure class="aov"
/// data-layer="NAME">`; the unnamed RGB layer and a layer named "beauty" both show as "beauty".
/// Throws InputError naming an EXR that cannot be read.
std::string build_aov_html(const FrameCatalog& catalog, std::optional<int> requested_frame);

}  // namespace steadylight
