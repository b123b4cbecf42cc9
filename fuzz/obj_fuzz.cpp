// Fuzzes the OBJ mesh reader (tinyobjloader and what we make of its result).
#include "fuzz_harness.h"
#include "steadylight/scene/shapes.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace steadylight;
    const std::string path = fuzz::write_input(data, size, "mesh.obj");
    fuzz::expect_clear_errors([&] { load_obj_mesh(path); });
    return 0;
}
