// Fuzzes the reading of an output folder's settings file (run/settings_file.h): the file from an
// earlier run is the input, met by a run of its own "render" settings when it parses (so the two
// agree and their frame lists are merged) and by a run of other settings.
#include <nlohmann/json.hpp>

#include "fuzz_harness.h"
#include "steadylight/run/settings_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace steadylight;
    const nlohmann::json earlier = nlohmann::json::parse(data, data + size, nullptr, false);
    nlohmann::json same = {
        {"render", earlier.is_object() ? earlier.value("render", nlohmann::json()) : nlohmann::json()},
        {"frames", "2-4"}};
    const nlohmann::json other = {{"render", {{"method", "photon"}, {"format_version", settings_format_version}}},
                                  {"frames", "0"}};
    for (const nlohmann::json& now : {same, other}) {
        const std::string path = fuzz::write_input(data, size, "cornell.settings.json");
        fuzz::expect_clear_errors([&] { write_settings_file(path, now, false); });
    }
    return 0;
}
