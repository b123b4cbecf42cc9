// glTF materials (gltf_materials.h).
#include "steadylight/scene/gltf_materials.h"

#include <algorithm>
#include <set>
#include <utility>

#include <fmt/format.h>

namespace steadylight::gltf {
namespace {

/// The number `key` inside extension `name`, or `fallback` when either is absent.
double extension_number(const tinygltf::ExtensionMap& extensions, const std::string& name,
                        const std::string& key, double fallback) {
    const auto it = extensions.find(name);
    if (it == extensions.end() || !it->second.IsObject()) return fallback;
    const tinygltf::Value& value = it->second.Get(key);
    return value.IsNumber() ? value.GetNumberAsDouble() : fallback;
}


void warn_ignored_features(const GltfFile& file, const tinygltf::Material& m,
                           const std::string& where) {
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    const std::pair<bool, const char*> features[] = {
        {pbr.baseColorTexture.index >= 0, "base colour textures are ignored"},
        {pbr.metallicRoughnessTexture.index >= 0, "metallic-roughness textures are ignored"},
        {pbr.metallicFactor > 0, "metallic factors are ignored; metals render as Lambertian"},
        {pbr.roughnessFactor < 1,
         "roughness factors are ignored; surfaces are Lambertian or smooth glass"},
        {m.normalTexture.index >= 0, "normal maps are ignored"},
        {m.occlusionTexture.index >= 0, "occlusion maps are ignored"},
        {m.emissiveTexture.index >= 0, "emissive textures are ignored"},
        {m.alphaMode != "OPAQUE", "alpha modes other than OPAQUE are ignored"},
    };
    for (const auto& [used, what] : features)
        if (used) file.warn_once(what, where);
    static const std::set<std::string> supported = {
        "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength"};
    for (const auto& [name, value] : m.extensions)
        if (!supported.contains(name))
            file.warn_once("material extension " + name + " is ignored", where);
}

MaterialDesc convert_material(const GltfFile& file, const tinygltf::Material& m,
                              const std::string& where) {
    MaterialDesc desc;
    const Rgb base_colour = clamped_rgb(m.pbrMetallicRoughness.baseColorFactor);
    if (extension_number(m.extensions, "KHR_materials_transmission", "transmissionFactor", 0) <=
        0) {
        desc.reflectance = base_colour;
        return desc;
    }
    desc.type = MaterialType::dielectric;
    desc.transmittance = base_colour;
    desc.ior = float(extension_number(m.extensions, "KHR_materials_ior", "ior", 1.5));
    // KHR_materials_ior allows 0 for "infinitely dense", which a smooth dielectric cannot be.
    if (!(desc.ior >= 1)) {
        spdlog::warn("{}: {}: ior {} is not supported, using 1.5", file.path, where, desc.ior);
        desc.ior = 1.5f;
    }
    return desc;
}

Rgb emission_of(const tinygltf::Material& m) {
    const float strength = float(
        extension_number(m.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1));
    return clamped_rgb(m.emissiveFactor) * std::max(strength, 0.0f);
}

/// `name`, or `name#index` (repeated) when SceneDesc already has a material of that name.
std::string unique_material_name(const SceneDesc& desc, const std::string& name, int index) {
    const auto taken = [&](const std::string& candidate) {
        return std::any_of(desc.materials.begin(), desc.materials.end(),
                           [&](const MaterialDesc& m) { return m.name == candidate; });
    };
    const std::string suffix = fmt::format("#{}", index);  // not "#" + to_string: GCC bug 105329
    std::string unique = name;
    while (taken(unique)) unique += suffix;
    return unique;
}

/// Adds glTF material `index` (or the default grey for -1) to `desc`.

}  // namespace

Rgb clamped_rgb(const std::vector<double>& v) {
    if (v.size() < 3) return {};
    const auto c = [&](size_t i) { return std::clamp(float(v[i]), 0.0f, 1.0f); };
    return {c(0), c(1), c(2)};
}

ImportedMaterial import_material(const GltfFile& file, int index, SceneDesc& desc) {
    if (index >= int(file.model.materials.size()))
        file.fail("material " + std::to_string(index), "material index out of range");
    ImportedMaterial imported{.index = int(desc.materials.size())};
    if (index < 0) {
        desc.materials.push_back({.name = unique_material_name(desc, "(glTF default)", index)});
        return imported;
    }
    const tinygltf::Material& m = file.model.materials[size_t(index)];
    const std::string where = describe("material", size_t(index), m.name);
    warn_ignored_features(file, m, where);
    MaterialDesc material = convert_material(file, m, where);
    material.name = unique_material_name(
        desc, m.name.empty() ? "material " + std::to_string(index) : m.name, index);
    desc.materials.push_back(material);
    imported.emission = emission_of(m);
    imported.two_sided = m.doubleSided;
    return imported;
}

}  // namespace steadylight::gltf
