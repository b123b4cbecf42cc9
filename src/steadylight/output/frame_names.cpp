#include "steadylight/output/frame_names.h"

#include <filesystem>

#include <fmt/format.h>

namespace steadylight {

std::string frame_file_name(const std::string& out_dir, const std::string& scene_name, int frame,
                            const std::string& extension) {
    return (std::filesystem::path(out_dir) / fmt::format("{}_{:04d}.{}", scene_name, frame, extension)).string();
}

}  // namespace steadylight
