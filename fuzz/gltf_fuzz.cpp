// Fuzzes the glTF importer (docs/gltf.md) on a whole file: tinygltf's parsing, our accessors,
// materials, textures (images decoded) and animations, and the scene checks. Built twice, for
// .glb (FUZZ_GLTF_EXTENSION ".glb") and for .gltf text.
#include "fuzz_harness.h"
#include "steadylight/scene/scene_desc.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace steadylight;
    const std::string path = fuzz::write_input(data, size, std::string("scene") + FUZZ_GLTF_EXTENSION);
    fuzz::expect_clear_errors([&] { validate(load_scene_desc(path)); });
    return 0;
}
