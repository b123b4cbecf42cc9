// The glTF file being imported, shared by the parts of the glTF importer (gltf_loader.cpp,
// gltf_accessors.cpp, gltf_materials.cpp, gltf_animation.cpp): its tinygltf model, and the
// errors and once-per-kind warnings that name the file and the element.
#pragma once

#include <set>
#include <string>

#include <spdlog/spdlog.h>
#include <tiny_gltf.h>

#include "steadylight/base/error.h"

namespace steadylight::gltf {

/// "node 3 \"Ball\"", or "node 3" for an unnamed element.
inline std::string describe(const std::string& kind, size_t index, const std::string& name) {
    return kind + " " + std::to_string(index) + (name.empty() ? "" : " \"" + name + "\"");
}

/// True when the image holds decoded 8-bit RGBA pixels (gltf_loader.cpp decode_gltf_image).
inline bool is_decoded(const tinygltf::Image& image) {
    return image.component == 4 && image.bits == 8 && image.width > 0 && image.height > 0 &&
           image.image.size() == size_t(image.width) * size_t(image.height) * 4;
}

/// The file being imported, for reading its data and for messages about it.
struct GltfFile {
    std::string path;
    tinygltf::Model model;
    int image_base = 0;  // SceneDesc::images index of the file's image 0
    mutable std::set<std::string> warned;

    /// Throws InputError at "<path>: <element>".
    [[noreturn]] void fail(const std::string& element, const std::string& what) const {
        throw InputError(path + ": " + element, what);
    }
    /// Logs "<path>: <what> (<element>)" the first time `what` comes up, so that a feature
    /// used by a thousand materials is reported once.
    void warn_once(const std::string& what, const std::string& element) const {
        if (!warned.insert(what).second) return;
        if (element.empty())
            spdlog::warn("{}: {}", path, what);
        else
            spdlog::warn("{}: {} ({})", path, what, element);
    }
};

}  // namespace steadylight::gltf
