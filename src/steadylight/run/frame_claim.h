// Frame claims: several `steadylight render` processes, on one machine or many, pointed at one
// shared output folder share its frames without a scheduler, as Blender's "placeholders, no
// overwrite" lets its users do. Before rendering a frame a process claims it: it takes the lock
// file `<scene>_<frame:04>.claim` (base/lock_file.h: host, pid and time as JSON, refreshed while
// the frame renders, taken over when its holder is dead). A process that finds a frame claimed
// leaves it alone. Only the holder of a frame's claim removes that frame's stale `.partial`
// files, when it took the claim over from a dead process (one killed outright leaves them; one
// that fails or is interrupted removes its own), and it releases the claim when the frame's
// manifest is written (or the frame failed). See docs/farm.md.
#pragma once

#include <string>

#include "steadylight/base/lock_file.h"

namespace steadylight {

/// `<out>/<scene>_<frame:04>.claim`.
std::string frame_claim_name(const std::string& out_dir, const std::string& scene_name, int frame);

/// \brief Claims a frame of `out_dir`, taking over a dead claim and then removing the frame's
/// stale `.partial` files. `times` are for tests. Throws OutputError naming the file it cannot
/// write.
LockAttempt try_claim_frame(const std::string& out_dir, const std::string& scene_name, int frame,
                            const LockTimes& times = lock_times());

}  // namespace steadylight
