// Where a frame's files go: `<out>/<scene>_<frame:04>.<ext>`.
#pragma once

#include <string>

namespace steadylight {

std::string frame_file_name(const std::string& out_dir, const std::string& scene_name, int frame,
                            const std::string& extension);

}  // namespace steadylight
