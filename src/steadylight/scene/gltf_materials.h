// glTF materials (glTF 2.0 §3.9) as steadylight materials: base colour as Lambertian
// reflectance, KHR_materials_transmission with KHR_materials_ior as a smooth dielectric, and
// emissiveFactor x KHR_materials_emissive_strength as the emission of the objects using it.
// Features without a counterpart are warned about once per file (docs/gltf.md).
#pragma once

#include <string>
#include <vector>

#include "steadylight/base/color.h"
#include "steadylight/scene/gltf_file.h"
#include "steadylight/scene/scene_desc.h"

namespace steadylight::gltf {

/// What a glTF material becomes: an entry in SceneDesc::materials plus the emission that the
/// objects using it carry (emission belongs to objects in SceneDesc, to materials in glTF).
struct ImportedMaterial {
    int index = 0;
    Rgb emission;
    bool two_sided = false;
};

/// The first three numbers of `v` clamped to [0, 1]; black when there are fewer.
Rgb clamped_rgb(const std::vector<double>& v);

/// Adds glTF material `index` (-1: the default grey) to `desc.materials`.
ImportedMaterial import_material(const GltfFile& file, int index, SceneDesc& desc);

}  // namespace steadylight::gltf
