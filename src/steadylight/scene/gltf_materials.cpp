// glTF materials (gltf_materials.h).
#include "steadylight/scene/gltf_materials.h"

#include <algorithm>
#include <set>
#include <utility>

#include <fmt/format.h>

namespace steadylight::gltf {
namespace {

/// The number `key` inside extension `name`, or `fallback` when either is absent.
double extension_number(const tinygltf::ExtensionMap& extensions, const std::string& name, const std::string& key,
                        double fallback) {
    const auto it = extensions.find(name);
    if (it == extensions.end() || !it->second.IsObject()) return fallback;
    const tinygltf::Value& value = it->second.Get(key);
    return value.IsNumber() ? value.GetNumberAsDouble() : fallback;
}

/// KHR_materials_volume on a transmissive material: Beer-Lambert absorption inside. A thickness
/// of 0 (the default) says the material is thin-walled, which absorbs nothing; any other
/// thickness only says that the mesh encloses a volume, since absorption follows the distance
/// rays really travel inside (docs/materials.md, "Glass").
void set_volume(const GltfFile& file, const tinygltf::Material& m, MaterialDesc& desc, const std::string& where) {
    const auto it = m.extensions.find("KHR_materials_volume");
    if (it == m.extensions.end() || !it->second.IsObject()) return;
    const tinygltf::Value& volume = it->second;
    if (extension_number(m.extensions, "KHR_materials_volume", "thicknessFactor", 0) <= 0) return;
    if (volume.Has("thicknessTexture")) file.warn_once("volume thickness textures are ignored", where);
    const float distance = float(extension_number(m.extensions, "KHR_materials_volume", "attenuationDistance", 0));
    if (distance > 0) desc.attenuation_distance = distance;  // absent (or invalid): infinite, no absorption
    const tinygltf::Value& colour = volume.Get("attenuationColor");
    const auto channel = [&](int c) { return std::clamp(float(colour.Get(c).GetNumberAsDouble()), 0.0f, 1.0f); };
    if (colour.IsArray() && colour.ArrayLen() >= 3) desc.attenuation_color = {channel(0), channel(1), channel(2)};
}

void warn_ignored_features(const GltfFile& file, const tinygltf::Material& m, const std::string& where) {
    if (m.occlusionTexture.index >= 0) file.warn_once("occlusion maps are ignored (occlusion is ray traced)", where);
    static const std::set<std::string> supported = {"KHR_materials_transmission", "KHR_materials_ior",
                                                    "KHR_materials_emissive_strength", "KHR_materials_specular",
                                                    "KHR_materials_volume"};
    for (const auto& [name, value] : m.extensions)
        if (!supported.contains(name)) file.warn_once("material extension " + name + " is ignored", where);
}

/// The vector `key` inside a JSON object value, or `fallback`.
Vec2 value_vec2(const tinygltf::Value& object, const std::string& key, Vec2 fallback) {
    const tinygltf::Value& v = object.Get(key);
    if (!v.IsArray() || v.ArrayLen() < 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber()) return fallback;
    return {float(v.Get(0).GetNumberAsDouble()), float(v.Get(1).GetNumberAsDouble())};
}

TextureWrap wrap_mode(int gl_wrap) {
    switch (gl_wrap) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
            return TextureWrap::clamp_to_edge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
            return TextureWrap::mirrored_repeat;
    }
    return TextureWrap::repeat;
}

/// A material's texture reference: its image, sampler and KHR_texture_transform.
TextureRef texture_ref(const GltfFile& file, int texture, int texcoord, const tinygltf::ExtensionMap& extensions,
                       const std::string& where) {
    TextureRef ref;
    if (texture < 0) return ref;
    const tinygltf::Model& model = file.model;
    if (size_t(texture) >= model.textures.size()) file.fail(where, "texture index out of range");
    const tinygltf::Texture& t = model.textures[size_t(texture)];
    if (t.source < 0 || size_t(t.source) >= model.images.size() || !is_decoded(model.images[size_t(t.source)])) {
        file.warn_once("textures without a PNG or JPEG image are ignored", where);
        return ref;
    }
    ref.image = file.image_base + t.source;
    ref.texcoord = texcoord;
    if (t.sampler >= 0 && size_t(t.sampler) < model.samplers.size()) {
        const tinygltf::Sampler& sampler = model.samplers[size_t(t.sampler)];
        ref.wrap_s = wrap_mode(sampler.wrapS);
        ref.wrap_t = wrap_mode(sampler.wrapT);
        if (sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) ref.filter = TextureFilter::nearest;
    }
    if (const auto it = extensions.find("KHR_texture_transform"); it != extensions.end() && it->second.IsObject()) {
        const tinygltf::Value& x = it->second;
        ref.offset = value_vec2(x, "offset", {});
        ref.scale = value_vec2(x, "scale", {1, 1});
        if (x.Get("rotation").IsNumber()) ref.rotation = float(x.Get("rotation").GetNumberAsDouble());
        if (x.Get("texCoord").IsNumber()) ref.texcoord = x.Get("texCoord").GetNumberAsInt();
    }
    if (ref.texcoord < 0 || ref.texcoord > 1) {
        file.warn_once("texture coordinate sets other than TEXCOORD_0 and _1 are ignored", where);
        return {};
    }
    return ref;
}

AlphaMode alpha_mode(const GltfFile& file, const std::string& mode, const std::string& where) {
    if (mode == "MASK") return AlphaMode::mask;
    if (mode == "BLEND") {
        file.warn_once("alpha mode BLEND is rendered as MASK (cut out below alphaCutoff)", where);
        return AlphaMode::blend;
    }
    return AlphaMode::opaque;
}

MaterialDesc convert_material(const GltfFile& file, const tinygltf::Material& m, const std::string& where) {
    MaterialDesc desc;
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    const Rgb base_colour = clamped_rgb(pbr.baseColorFactor);
    if (extension_number(m.extensions, "KHR_materials_transmission", "transmissionFactor", 0) <= 0) {
        desc.type = MaterialType::pbr;
        desc.reflectance = base_colour;
        desc.alpha = pbr.baseColorFactor.size() > 3 ? std::clamp(float(pbr.baseColorFactor[3]), 0.0f, 1.0f) : 1.0f;
        desc.metallic = std::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
        desc.roughness = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
        desc.ior = float(extension_number(m.extensions, "KHR_materials_ior", "ior", 1.5));
        if (!(desc.ior >= 1)) desc.ior = 1.5f;
        // KHR_materials_specular: the coat's Fresnel is scaled by specularFactor, and its
        // normal-incidence value by specularColorFactor (taken as its largest channel).
        const float specular = float(extension_number(m.extensions, "KHR_materials_specular", "specularFactor", 1));
        float colour = 1;
        if (const auto it = m.extensions.find("KHR_materials_specular");
            it != m.extensions.end() && it->second.IsObject()) {
            const tinygltf::Value& c = it->second.Get("specularColorFactor");
            if (c.IsArray() && c.ArrayLen() >= 3) {
                colour = 0;
                for (int i = 0; i < 3; ++i) colour = std::max(colour, float(c.Get(i).GetNumberAsDouble()));
            }
        }
        desc.specular = std::clamp(specular, 0.0f, 1.0f);
        desc.specular_color = std::clamp(colour, 0.0f, 1.0f);
        desc.alpha_mode = alpha_mode(file, m.alphaMode, where);
        desc.alpha_cutoff = float(m.alphaCutoff);
        desc.base_color_texture = texture_ref(file, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                              pbr.baseColorTexture.extensions, where);
        desc.metallic_roughness_texture =
            texture_ref(file, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                        pbr.metallicRoughnessTexture.extensions, where);
        desc.normal_texture =
            texture_ref(file, m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions, where);
        desc.normal_scale = float(m.normalTexture.scale);
        desc.emissive_texture =
            texture_ref(file, m.emissiveTexture.index, m.emissiveTexture.texCoord, m.emissiveTexture.extensions, where);
        return desc;
    }
    if (pbr.baseColorTexture.index >= 0 || m.normalTexture.index >= 0)
        file.warn_once("textures on transmissive (glass) materials are ignored", where);
    desc.type = MaterialType::dielectric;
    desc.transmittance = base_colour;
    desc.ior = float(extension_number(m.extensions, "KHR_materials_ior", "ior", 1.5));
    // KHR_materials_ior allows 0 for "infinitely dense", which a smooth dielectric cannot be.
    if (!(desc.ior >= 1)) {
        spdlog::warn("{}: {}: ior {} is not supported, using 1.5", file.path, where, desc.ior);
        desc.ior = 1.5f;
    }
    // Rough glass (make_bsdf makes glass below GGX's smallest roughness smooth).
    desc.roughness = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
    set_volume(file, m, desc, where);
    return desc;
}

Rgb emission_of(const tinygltf::Material& m) {
    const float strength =
        float(extension_number(m.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1));
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
        // glTF §3.9.6's default material: white, metallic 1, roughness 1 -- but a renderer
        // shows it as plain grey in practice, so it stays the Lambertian 0.8 it always was.
        desc.materials.push_back({.name = unique_material_name(desc, "(glTF default)", index)});
        return imported;
    }
    const tinygltf::Material& m = file.model.materials[size_t(index)];
    const std::string where = describe("material", size_t(index), m.name);
    warn_ignored_features(file, m, where);
    MaterialDesc material = convert_material(file, m, where);
    material.name = unique_material_name(desc, m.name.empty() ? "material " + std::to_string(index) : m.name, index);
    desc.materials.push_back(material);
    imported.emission = emission_of(m);
    imported.two_sided = m.doubleSided;
    return imported;
}

}  // namespace steadylight::gltf
