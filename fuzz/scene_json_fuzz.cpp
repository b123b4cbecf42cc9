// Fuzzes the JSON scene reader (docs/scene-format.md): the whole load of scene.json, with the
// repository's scenes folder linked beside it (STEADYLIGHT_FUZZ_FILES) for its meshes.
#include "fuzz_harness.h"
#include "steadylight/scene/scene_desc.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace steadylight;
    const std::string path = fuzz::write_input(data, size, "scene.json");
    fuzz::expect_clear_errors([&] { validate(load_scene_desc(path)); });
    return 0;
}
