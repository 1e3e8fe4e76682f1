// Runs one `kiln batch` job in a child process: the kiln binary itself (/proc/self/exe, through
// posix_spawn, never a bare fork of a multi-threaded process) with the job's `kiln render`
// arguments. A job that crashes (a library's assertion, a segfault, the OOM killer) then takes
// only itself down, and the batch goes on. The child's messages and progress come back through
// a pipe and reach stderr under the job's name. App layer only.
#pragma once

#include <string>
#include <vector>

#include "app/batch_command.h"

namespace kiln {

// How the child ended.
struct child_outcome {
  bool started = false;  // false: the child could not be started (error says why)
  int exit_code = -1;    // when it exited
  int signal = 0;        // when a signal killed it (a crash)
  std::string error;     // its last message line (without "kiln: "), or why it could not start
};

// The `kiln render` arguments (after the program name) that run a job with options (its
// batch_job_options) in a child: the asset, -o, the canonical render arguments, --threads, the
// preview, and the hidden --batch-command-line that records the job's own command line.
// progress_interval: seconds between progress lines.
std::vector<std::string> child_render_arguments(const render_options& options, double progress_interval);

// Runs the job with options in a child and waits for it. Lines the child prints go to stderr as
// "kiln batch: LABEL: ..." (none when quiet); on a terminal its progress becomes one line that
// rewrites itself. The last line is kept as the error when the child fails.
child_outcome run_job_in_child(const render_options& options, const std::string& label, bool quiet);

// "SIGABRT" for 6: the signal's abbreviation, or "signal N".
std::string signal_name(int signo);

}  // namespace kiln
