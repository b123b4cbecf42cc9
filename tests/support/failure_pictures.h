// What an image test leaves behind when it fails: the rendered image, the reference and their
// difference, as EXR and PNG under the build folder, with their paths printed, so that a failure
// can be looked at rather than only read as a figure.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "steadylight/output/image_writer.h"

namespace steadylight::testing {

/// The folder a failed test's pictures go to: `<build>/test_failures/<suite>.<test>`, the
/// parameterised test's slashes made dashes.
inline std::filesystem::path failure_folder() {
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(test->test_suite_name()) + "." + test->name();
    for (char& c : name)
        if (c == '/') c = '-';
    return std::filesystem::path(STEADYLIGHT_BINARY_DIR) / "test_failures" / name;
}

/// |image - reference| per channel, so that a PNG of it shows where they part.
inline Image absolute_difference(const Image& image, const Image& reference) {
    Image difference(image.width, image.height);
    for (size_t i = 0; i < image.pixels.size() && i < reference.pixels.size(); ++i) {
        const Rgb a = image.pixels[i], b = reference.pixels[i];
        difference.pixels[i] = {std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)};
    }
    return difference;
}

/// When the running test has failed so far, writes `image`, `reference` and their difference
/// (image.exr/png, reference.exr/png, difference.exr/png; the difference's PNG 3 stops brighter,
/// so that small differences show) into failure_folder() and prints the paths. Call it after the
/// test's checks.
inline void keep_pictures_if_failed(const Image& image, const Image& reference) {
    if (!::testing::Test::HasFailure()) return;
    const std::filesystem::path folder = failure_folder();
    std::filesystem::create_directories(folder);
    const Image difference = absolute_difference(image, reference);
    for (const auto& [name, picture] :
         {std::pair{"image", &image}, {"reference", &reference}, {"difference", &difference}}) {
        const std::string base = (folder / name).string();
        write_exr(base + ".exr", *picture);
        write_png(base + ".png", *picture, {.exposure_ev = picture == &difference ? 3.0f : 0.0f});
        std::printf("failed: %s.png (and .exr)\n", base.c_str());
    }
}

}  // namespace steadylight::testing
