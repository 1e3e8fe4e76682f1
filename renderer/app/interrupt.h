// SIGINT/SIGTERM handling for the CLI: the first signal asks the render to stop (it stops within
// a pixel or 64 samples, the EXR writer never starts, no temporary file is left); a second signal
// kills the process at once with the default action. While `kiln batch` runs a job in a child
// process, every signal is also forwarded to that child, so it stops (or dies) the same way.
#pragma once

#include <sys/types.h>

#include <atomic>

namespace kiln {

// Installs the handlers. Call once, before rendering starts.
void install_interrupt_handlers();

// Becomes true when SIGINT or SIGTERM arrives.
const std::atomic<bool>& interrupt_requested();

// The signal that arrived (SIGINT or SIGTERM), or 0.
int interrupt_signal();

// Forwards every later SIGINT/SIGTERM to child (0: to nobody). Set it with the signals blocked
// (forwarding_guard) right after the child starts, clear it before the child is reaped.
void forward_interrupts_to(pid_t child);

// Blocks SIGINT and SIGTERM in this thread for its lifetime; a signal that arrives meanwhile is
// delivered (and forwarded) when it ends.
struct interrupt_block {
  interrupt_block();
  ~interrupt_block();
  interrupt_block(const interrupt_block&) = delete;
  interrupt_block& operator=(const interrupt_block&) = delete;
};

}  // namespace kiln
