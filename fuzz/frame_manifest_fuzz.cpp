// Fuzzes the frame manifest check of a resumed render (run/frame_manifest.h), in a folder that
// holds the files the seed manifest lists (fuzz/folders/frame_manifest via STEADYLIGHT_FUZZ_FILES).
#include "fuzz_harness.h"
#include "steadylight/run/frame_manifest.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace steadylight;
    fuzz::write_input(data, size, "cornell_0000.manifest.json");
    fuzz::expect_clear_errors([&] { check_frame_outputs(fuzz::folder().string(), "cornell", 0, "3d310e430bf1bf68"); });
    return 0;
}
