// Fuzzes world images (scene/world_image.h) read from a file: EXR through OpenEXR (every
// compression, tiled and scanline files, data windows anywhere), Radiance HDR through our own
// decoder, and the checks of size, shape and pixels; then builds the environment map of what was
// accepted and samples it, which must take any image the loader lets through. Seeds: tiny files
// made for the purpose, and Blender's forest.exr (CC0, Greg Zaal) averaged down to 64 x 32.
#include <cmath>
#include <cstdlib>

#include "fuzz_harness.h"
#include "steadylight/scene/environment_map.h"
#include "steadylight/scene/world_image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace steadylight;
    const std::string path = fuzz::write_input(data, size, "world");
    fuzz::expect_clear_errors([&] {
        const Image image = load_world_image(path);
        if (image.width != 2 * image.height || image.pixels.size() != size_t(image.width) * size_t(image.height))
            std::abort();
        const EnvironmentMap map(image, 1, 30);
        for (const Vec2 u : {Vec2{0.1f, 0.2f}, Vec2{0.5f, 0.5f}, Vec2{0.9f, 0.999f}})
            if (const auto sample = map.sample(u); sample && !(sample->pdf > 0 && std::isfinite(sample->pdf)))
                std::abort();
    });
    return 0;
}
