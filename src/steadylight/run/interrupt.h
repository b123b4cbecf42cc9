// Ctrl-C during a render. The first SIGINT or SIGTERM only sets the checkpoint flag
// (base/checkpoint.h): the render stops at its next checkpoint, drops the frame in progress and
// exits with 130 after saying how to resume. A second one exits at once (status 130); temporary
// `.partial` files may then stay behind, but never a truncated final file, as every file is
// renamed into place whole (base/atomic_file.h).
#pragma once

#include <optional>

namespace steadylight {

/// Installs the SIGINT and SIGTERM handlers described above.
void install_interrupt_handlers();

/// Test only: the value of STEADYLIGHT_TEST_INTERRUPT_AFTER_FRAMES. When set to N, the render
/// raises SIGINT itself inside frame N + 1 (after N frames are written, at the frame's second
/// phase), so that tests can interrupt a render deterministically.
std::optional<int> test_interrupt_after_frames();

}  // namespace steadylight
