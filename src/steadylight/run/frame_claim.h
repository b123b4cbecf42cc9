// Frame claims: several `steadylight render` processes, on one machine or many, pointed at one
// shared output folder share its frames without a scheduler, as Blender's "placeholders, no
// overwrite" lets its users do. Before rendering a frame a process claims it: it creates
// `<scene>_<frame:04>.claim` (host, pid and time, as JSON) while holding the folder's lock
// (settings_file.h), and refreshes the file's modification time every claim_refresh_s while the
// frame renders. A process that finds a frame claimed leaves it alone, unless the claim is dead:
//   - its host is this host and its process is gone: taken over at once;
//   - its file was not refreshed for claim_stale_s, judged by the file system's clock (the lock
//     file is touched and its time read back, so machines' clocks never meet): taken over.
// Only the holder of a frame's claim removes that frame's stale `.partial` files, when it took
// the claim over from a dead process (one killed outright leaves them; one that fails or is
// interrupted removes its own), and it removes the claim when the frame's manifest is written
// (or the frame failed). See docs/farm.md.
#pragma once

#include <memory>
#include <optional>
#include <string>

namespace steadylight {

constexpr double claim_refresh_s = 10;  // how often a holder touches its claim file
constexpr double claim_stale_s = 120;   // a claim not touched for this long is taken over

/// `<out>/<scene>_<frame:04>.claim`.
std::string frame_claim_name(const std::string& out_dir, const std::string& scene_name, int frame);

/// A claim this process holds; refreshed by a thread of its own while it lives, and removed
/// (when still this process's) when it goes away.
class FrameClaim {
public:
    struct Refresher;
    FrameClaim(std::string path, double refresh_s);
    ~FrameClaim();
    FrameClaim(const FrameClaim&) = delete;
    FrameClaim& operator=(const FrameClaim&) = delete;

private:
    std::string m_path;
    std::unique_ptr<Refresher> m_refresher;
};

/// What try_claim_frame found.
struct ClaimAttempt {
    std::unique_ptr<FrameClaim> claim;  // set when this process now holds the frame
    std::string holder;                 // else who does: "host vm, pid 123, refreshed 4 s ago"
    std::string taken_over;             // when a dead claim was taken over: whose and why
};

/// \brief Claims a frame of `out_dir` under the folder's lock, taking over a dead claim (see
/// above) and then removing the frame's stale `.partial` files. `stale_s` and
/// `refresh_s` are for tests. Throws std::runtime_error naming the file it cannot write.
ClaimAttempt try_claim_frame(const std::string& out_dir, const std::string& scene_name, int frame,
                             double stale_s = claim_stale_s, double refresh_s = claim_refresh_s);

}  // namespace steadylight
