// Fuzzes texture image decoding (stb_image, PNG and JPEG, with the size check before decoding).
#include "fuzz_harness.h"
#include "steadylight/scene/image_decoding.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const steadylight::DecodedImage image = steadylight::decode_image(data, size);
    if (image.rgba.size() != size_t(image.width) * size_t(image.height) * 4) std::abort();
    return 0;
}
