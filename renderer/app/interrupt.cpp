#include "app/interrupt.h"

#include <pthread.h>

#include <csignal>

#include "io/exr/atomic_write.h"

namespace kiln {

namespace {

// Lock-free atomics are async-signal-safe; nothing else is touched from the handler.
std::atomic<bool> requested{false};
std::atomic<int> signal_number{0};
std::atomic<pid_t> forward_to{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free);
static_assert(std::atomic<pid_t>::is_always_lock_free);

extern "C" void on_interrupt(int signo) {
  // kill(2) is async-signal-safe; the child (in its own process group, so a terminal's Ctrl-C
  // reaches only the batch) sees each signal exactly once.
  if (const pid_t child = forward_to.load(); child > 0) ::kill(child, signo);
  if (requested.exchange(true)) {
    // Second signal: the user insists. Fall back to the default action (terminate), leaving no
    // temporary file of a write in progress behind.
    remove_temporary_files_in_progress();
    std::signal(signo, SIG_DFL);
    std::raise(signo);
    return;
  }
  signal_number.store(signo);
}

sigset_t interrupt_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
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

void forward_interrupts_to(pid_t child) { forward_to.store(child); }

interrupt_block::interrupt_block() {
  const sigset_t set = interrupt_signals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

interrupt_block::~interrupt_block() {
  const sigset_t set = interrupt_signals();
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}

}  // namespace kiln
