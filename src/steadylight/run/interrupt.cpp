// SIGINT/SIGTERM handlers and the test-only interrupt hook (interrupt.h).
#include "steadylight/run/interrupt.h"

#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <string>

#include "steadylight/base/checkpoint.h"

namespace steadylight {
namespace {

extern "C" void on_interrupt_signal(int) {
    // Only async-signal-safe calls here (POSIX signal-safety(7)): an atomic store and _exit.
    if (interrupt_requested()) _exit(130);
    request_interrupt();
    constexpr char message[] =
        "\nsteadylight: stopping; the frame in progress is dropped (Ctrl-C again to quit at once)\n";
    [[maybe_unused]] const ssize_t ignored = write(STDERR_FILENO, message, sizeof(message) - 1);
}

}  // namespace

void install_interrupt_handlers() {
    struct sigaction action {};
    action.sa_handler = on_interrupt_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

std::optional<int> test_interrupt_after_frames() {
    const char* value = std::getenv("STEADYLIGHT_TEST_INTERRUPT_AFTER_FRAMES");
    if (!value || !*value) return std::nullopt;
    return std::atoi(value);
}

}  // namespace steadylight
