#include "app/batch_child.h"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>

#include "app/interrupt.h"
#include "job/option_table.h"
#include "job/option_values.h"
#include "job/render_fingerprint.h"

extern char** environ;

namespace kiln {

namespace {

constexpr const char* progress_prefix = "kiln: rendering ";
constexpr size_t max_error_bytes = 1000;

// Forwards the child's lines to stderr under the job's label. The latest message line is held
// back until the next one (or the end): when the child fails, it is the error, printed once by the
// batch's own job line instead.
struct relay {
  std::string label;
  bool quiet = false;
  bool terminal = false;
  bool progress_open = false;  // a rewriting progress line is on the terminal
  std::string partial;         // bytes after the last newline
  std::string held;            // the last message line, not yet printed

  void end_progress_line() {
    if (progress_open) std::fputc('\n', stderr);
    progress_open = false;
  }
  void print(const std::string& line) {
    if (quiet) return;
    end_progress_line();
    const std::string text = line.rfind("kiln: ", 0) == 0 ? line.substr(6) : line;
    std::fprintf(stderr, "kiln batch: %s: %s\n", label.c_str(), text.c_str());
  }
  void line(std::string text) {
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.rfind(progress_prefix, 0) == 0) {
      if (!held.empty()) print(held);  // the render goes on: the message was not its last
      held.clear();
      if (quiet) return;
      const std::string rest = text.substr(std::strlen(progress_prefix));
      if (terminal) {
        std::fprintf(stderr, "\rkiln batch: %s: rendering %s ", label.c_str(), rest.c_str());
        progress_open = true;
      } else {
        std::fprintf(stderr, "kiln batch: %s: rendering %s\n", label.c_str(), rest.c_str());
      }
      std::fflush(stderr);
      return;
    }
    if (!held.empty()) print(held);
    held = std::move(text);
  }
  void bytes(const char* data, size_t size) {
    partial.append(data, size);
    for (size_t newline; (newline = partial.find('\n')) != std::string::npos;) {
      line(partial.substr(0, newline));
      partial.erase(0, newline + 1);
    }
  }
  // At the child's end: flushes the rest; returns the held line when the child failed.
  std::string finish(bool failed) {
    if (!partial.empty()) line(partial);
    partial.clear();
    end_progress_line();
    std::string last = std::move(held);
    held.clear();
    if (!failed && !last.empty()) print(last);
    if (last.rfind("kiln: ", 0) == 0) last.erase(0, 6);
    // A library's assertion can be long; the summary keeps its start.
    if (last.size() > max_error_bytes) last = last.substr(0, max_error_bytes) + "...";
    return failed ? last : std::string();
  }
};

// The spawned child: its own process group (a terminal's Ctrl-C reaches the batch alone, which
// forwards it once), default signal actions and an empty signal mask, stdin from /dev/null,
// stdout and stderr into the pipe.
bool spawn_child(const std::vector<std::string>& arguments, int pipe_write, pid_t& pid, std::string& error) {
  std::vector<char*> argv;
  std::string program = "kiln";  // argv[0]: messages such as assertions read "kiln: ..."
  argv.push_back(program.data());
  std::vector<std::string> copies = arguments;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t files;
  posix_spawnattr_t attributes;
  posix_spawn_file_actions_init(&files);
  posix_spawnattr_init(&attributes);
  posix_spawn_file_actions_addopen(&files, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&files, pipe_write, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&files, pipe_write, STDERR_FILENO);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int s : {SIGINT, SIGTERM, SIGPIPE}) sigaddset(&defaults, s);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setpgroup(&attributes, 0);
  posix_spawnattr_setflags(&attributes,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  const int status = ::posix_spawn(&pid, "/proc/self/exe", &files, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attributes);
  if (status != 0) error = std::string("cannot start the job's process: ") + std::strerror(status);
  return status == 0;
}

std::string shell_quoted(const std::string& s) {
  if (!s.empty() &&
      s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=./,:") ==
          std::string::npos)
    return s;
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The `kiln render` line that renders the job, for the EXR header.
std::string render_command_line(const render_options& o) {
  std::string line = "kiln render " + shell_quoted(o.input) + " -o " + shell_quoted(o.output);
  for (const std::string& a : canonical_render_arguments(o, region_arguments::include))
    line += " " + shell_quoted(a);
  if (!o.preview.empty())
    line +=
        " --preview " + shell_quoted(o.preview) + " --preview-exposure " + std::to_string(o.preview_exposure);
  return line;
}

}  // namespace

std::string signal_name(int signo) {
  if (const char* name = ::sigabbrev_np(signo)) return std::string("SIG") + name;
  return "signal " + std::to_string(signo);
}

std::vector<std::string> child_render_arguments(const render_options& o, double progress_interval) {
  std::vector<std::string> a = {"render", o.input, "-o", o.output};
  for (std::string& argument : canonical_render_arguments(o, region_arguments::include))
    a.push_back(std::move(argument));
  if (o.threads) a.insert(a.end(), {"--threads", std::to_string(o.threads)});
  if (!o.preview.empty())
    a.insert(a.end(), {"--preview", o.preview, "--preview-exposure", exact_text(o.preview_exposure)});
  if (o.quiet) a.push_back("-q");
  a.insert(a.end(), {"--progress-interval", exact_text(progress_interval)});
  a.insert(a.end(), {"--batch-command-line", render_command_line(o)});
  return a;
}

child_outcome run_job_in_child(const render_options& options, const std::string& label, bool quiet) {
  child_outcome outcome;
  relay out;
  out.label = label;
  out.quiet = quiet;
  out.terminal = ::isatty(STDERR_FILENO);
  // On a terminal the line rewrites itself, so it may change often; a log gets one every few seconds.
  const double interval = out.terminal ? 0.25 : options.progress_interval;

  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    outcome.error = std::string("cannot create a pipe: ") + std::strerror(errno);
    return outcome;
  }
  pid_t pid = 0;
  {
    // A signal between the start and the forwarding waits, then reaches the child too.
    interrupt_block blocked;
    if (interrupt_requested()) {
      ::close(fds[0]);
      ::close(fds[1]);
      return outcome;
    }
    outcome.started = spawn_child(child_render_arguments(options, interval), fds[1], pid, outcome.error);
    if (outcome.started) forward_interrupts_to(pid);
  }
  ::close(fds[1]);
  if (!outcome.started) {
    ::close(fds[0]);
    return outcome;
  }

  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n > 0) {
      out.bytes(buffer, size_t(n));
    } else if (n == 0 || errno != EINTR) {
      break;  // the child closed its end: it is exiting
    }
  }
  ::close(fds[0]);

  // Wait without reaping, stop forwarding, then reap: a signal never reaches a recycled pid.
  siginfo_t info{};
  while (::waitid(P_PID, id_t(pid), &info, WEXITED | WNOWAIT) != 0 && errno == EINTR) {
  }
  forward_interrupts_to(0);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    outcome.signal = WTERMSIG(status);
  } else {
    outcome.exit_code = WEXITSTATUS(status);
  }
  outcome.error = out.finish(outcome.signal != 0 || outcome.exit_code != 0);
  return outcome;
}

}  // namespace kiln
