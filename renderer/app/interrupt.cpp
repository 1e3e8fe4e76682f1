#include "app/interrupt.h"

#include <csignal>

namespace kiln {

namespace {

// Lock-free atomics are async-signal-safe; nothing else is touched from the handler.
std::atomic<bool> requested{false};
std::atomic<int> signal_number{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free);

extern "C" void on_interrupt(int signo) {
  if (requested.exchange(true)) {
    // Second signal: the user insists. Fall back to the default action (terminate).
    std::signal(signo, SIG_DFL);
    std::raise(signo);
    return;
  }
  signal_number.store(signo);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

const std::atomic<bool>& interrupt_requested() { return requested; }

int interrupt_signal() { return signal_number.load(); }

}  // namespace kiln
