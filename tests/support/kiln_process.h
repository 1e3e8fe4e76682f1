// Starts the kiln binary as a child process that a test can signal, limit and wait for with a
// deadline, so that a regression that hangs fails the test instead of stalling the suite.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace kiln::testing {

// A kiln process started with fork/exec; stderr goes to stderr_path, stdin and stdout to /dev/null.
struct child_process {
  pid_t pid = -1;
  std::string stderr_path;

  // Waits for the exit; returns the exit code, or minus the signal number when a signal killed
  // the process (so a handled signal, exit 128 + n, and an unhandled one differ).
  int wait() const;

  // As wait(), but kills the process (SIGKILL) and returns nothing when it has not ended after
  // `seconds`: a hang becomes a failed expectation.
  std::optional<int> wait_at_most(double seconds) const;

  // True once the process catches signo (its handler is installed), read from /proc.
  bool catches(int signo) const;

  // True while the process holds a descriptor open on path (read from /proc/PID/fd).
  bool has_open(const std::string& path) const;

  std::string stderr_text() const;
};

// Starts kiln with arguments; stderr goes to folder/stderr.txt; prepare runs in the child just
// before exec (resource limits).
child_process start_kiln(const std::vector<std::string>& arguments, const std::string& folder,
                         const std::function<void()>& prepare = {});

// How a run of kiln ended: its exit code (-1000: killed at the deadline), its stderr, how long it
// took and its peak resident memory.
struct measured_run {
  int exit_code = -1000;
  std::string stderr_text;
  double seconds = 0.0;
  long peak_kib = 0;
};

// Runs kiln with args (stderr in folder), killing it after `seconds`. address_space_bytes (0: no
// limit) caps its address space, except under AddressSanitizer, whose shadow memory needs
// terabytes of it (the peak RSS still bounds such a run), so a read that never ends fails in memory
// rather than take the machine's.
measured_run run_measured(const std::vector<std::string>& args, const std::string& folder, double seconds,
                          uint64_t address_space_bytes);

}  // namespace kiln::testing
