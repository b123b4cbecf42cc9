// The interrupt flag and the progress listener behind the render's checkpoints (checkpoint.h).
#include "steadylight/base/checkpoint.h"

#include <atomic>

namespace steadylight {
namespace {

// Signal handlers may only touch lock-free atomics (C++20 [support.signal]).
std::atomic<bool> g_interrupt{false};
static_assert(std::atomic<bool>::is_always_lock_free);
std::atomic<CheckpointListener*> g_listener{nullptr};

}  // namespace

void request_interrupt() { g_interrupt.store(true, std::memory_order_relaxed); }
bool interrupt_requested() { return g_interrupt.load(std::memory_order_relaxed); }
void clear_interrupt() { g_interrupt.store(false, std::memory_order_relaxed); }

void throw_if_interrupted() {
    if (interrupt_requested()) throw RenderInterrupted();
}

void set_checkpoint_listener(CheckpointListener* listener) { g_listener.store(listener); }

void begin_phase(std::string_view name) {
    if (CheckpointListener* listener = g_listener.load()) listener->phase(name);
    throw_if_interrupted();
}

void report_work(long done, long total) {
    if (CheckpointListener* listener = g_listener.load()) listener->work(done, total);
}

}  // namespace steadylight
