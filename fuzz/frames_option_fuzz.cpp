// Fuzzes the --frames option's parser (run/frame_selection.h) and the frame list it selects from
// a scene of 1000 frames.
#include "fuzz_harness.h"
#include "steadylight/run/frame_selection.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace steadylight;
    const std::string text(reinterpret_cast<const char*>(data), size);
    fuzz::expect_clear_errors([&] {
        const std::vector<int> frames = select_frames(parse_frame_selection(text), 1000);
        if (select_frames(parse_frame_selection(format_frame_list(frames)), 1000) != frames) std::abort();
    });
    return 0;
}
