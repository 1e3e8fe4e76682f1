// SIGINT/SIGTERM handling for the CLI: the first signal asks the render to stop (it stops within
// a pixel or 64 samples, the EXR writer never starts, no temporary file is left); a second signal
// kills the process at once with the default action.
#pragma once

#include <atomic>

namespace kiln {

// Installs the handlers. Call once, before rendering starts.
void install_interrupt_handlers();

// Becomes true when SIGINT or SIGTERM arrives.
const std::atomic<bool>& interrupt_requested();

// The signal that arrived (SIGINT or SIGTERM), or 0.
int interrupt_signal();

}  // namespace kiln
