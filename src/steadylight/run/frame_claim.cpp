// Claiming frames in a shared output folder (frame_claim.h).
#include "steadylight/run/frame_claim.h"

#include <filesystem>
#include <system_error>

#include <spdlog/spdlog.h>

#include "steadylight/output/frame_names.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

/// Removes the frame's `.partial` files: left by a process that died inside the frame.
void remove_stale_partials(const std::string& out_dir, const std::string& scene_name, int frame) {
    const std::string prefix = fs::path(frame_file_name(out_dir, scene_name, frame, "")).filename().string();
    for (const fs::directory_entry& entry : fs::directory_iterator(out_dir)) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with(prefix) && name.ends_with(".partial")) {
            std::error_code ignored;
            if (fs::remove(entry.path(), ignored)) spdlog::info("frame {}: removed the stale {}", frame, name);
        }
    }
}

}  // namespace

std::string frame_claim_name(const std::string& out_dir, const std::string& scene_name, int frame) {
    return frame_file_name(out_dir, scene_name, frame, "claim");
}

LockAttempt try_claim_frame(const std::string& out_dir, const std::string& scene_name, int frame,
                            const LockTimes& times) {
    LockAttempt attempt = LockFile::try_lock(frame_claim_name(out_dir, scene_name, frame), times);
    // Its holder may have died inside the frame. (A process that fails or is interrupted removes
    // its own temporary files; only one killed outright leaves them, and its claim.)
    if (!attempt.taken_over.empty()) remove_stale_partials(out_dir, scene_name, frame);
    return attempt;
}

}  // namespace steadylight
