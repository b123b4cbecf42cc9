// Checkpoints of a long render: the places where it reports progress and where it may stop.
// A signal handler (run/interrupt.h) only sets a flag; the render notices it at the next
// checkpoint — the start of a phase, or of a tile or chunk of a parallel loop (base/parallel.h) —
// and unwinds with RenderInterrupted, so the frame in progress is dropped before anything of it
// is written. Progress goes to one listener (the console, run/console.h), if any.
#pragma once

#include <exception>
#include <string_view>

namespace steadylight {

/// Thrown at a checkpoint after an interrupt was requested. Not an error: main exits with 130.
class RenderInterrupted : public std::exception {
public:
    const char* what() const noexcept override { return "interrupted"; }
};

/// Asks the render to stop at its next checkpoint. Async-signal-safe (a lock-free atomic store).
void request_interrupt();
bool interrupt_requested();
/// Forgets a request (tests; a program that renders again after an interrupt).
void clear_interrupt();
/// Throws RenderInterrupted when an interrupt was requested.
void throw_if_interrupted();

/// Receives the render's progress. Calls may come from several threads at once.
class CheckpointListener {
public:
    virtual ~CheckpointListener() = default;
    /// A named phase of the current frame starts ("photons", "influence", "L_y", "shading", ...).
    virtual void phase(std::string_view name) = 0;
    /// Within the current parallel loop, `done` of `total` tiles or chunks are finished.
    virtual void work(long done, long total) = 0;
};

/// Installs `listener` (nullptr: none); the caller keeps it alive while it is installed.
void set_checkpoint_listener(CheckpointListener* listener);

/// Installs a listener for the lifetime of the scope.
class ScopedCheckpointListener {
public:
    explicit ScopedCheckpointListener(CheckpointListener* listener) { set_checkpoint_listener(listener); }
    ~ScopedCheckpointListener() { set_checkpoint_listener(nullptr); }
    ScopedCheckpointListener(const ScopedCheckpointListener&) = delete;
    ScopedCheckpointListener& operator=(const ScopedCheckpointListener&) = delete;
};

/// Checkpoint at the start of phase `name`: tells the listener, then throws RenderInterrupted
/// when an interrupt was requested.
void begin_phase(std::string_view name);
/// Checkpoint inside a parallel loop: tells the listener (thread-safe).
void report_work(long done, long total);

}  // namespace steadylight
