#include "support/kiln_process.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace kiln::testing {

namespace {

int decode(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status); }

}  // namespace

int child_process::wait() const {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return decode(status);
}

std::optional<int> child_process::wait_at_most(double seconds) const {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return decode(status);
}

bool child_process::catches(int signo) const {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (signo - 1)) & 1u;
  return false;
}

bool child_process::has_open(const std::string& path) const {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/fd", ec)) {
    std::error_code link_ec;
    if (std::filesystem::read_symlink(entry.path(), link_ec) == path) return true;
  }
  return false;
}

std::string child_process::stderr_text() const {
  std::ifstream in(stderr_path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

child_process start_kiln(const std::vector<std::string>& arguments, const std::string& folder,
                         const std::function<void()>& prepare) {
  child_process child;
  child.stderr_path = folder + "/stderr.txt";
  std::vector<std::string> argv_storage{KILN_BINARY};
  argv_storage.insert(argv_storage.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  child.pid = ::fork();
  if (child.pid == 0) {
    int err = ::open(child.stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(err, STDERR_FILENO);
    int null = ::open("/dev/null", O_RDWR);
    ::dup2(null, STDIN_FILENO);
    ::dup2(null, STDOUT_FILENO);
    if (prepare) prepare();
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return child;
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool limit_address_space = false;
#else
constexpr bool limit_address_space = true;
#endif

measured_run run_measured(const std::vector<std::string>& args, const std::string& folder, double seconds,
                          uint64_t address_space_bytes) {
  const auto start = std::chrono::steady_clock::now();
  const child_process child = start_kiln(args, folder, [address_space_bytes] {
    if (!limit_address_space || !address_space_bytes) return;
    const rlimit limit{rlim_t(address_space_bytes), rlim_t(address_space_bytes)};
    ::setrlimit(RLIMIT_AS, &limit);
  });
  measured_run run;
  int status = 0;
  rusage usage{};
  while (::wait4(child.pid, &status, WNOHANG, &usage) == 0) {
    if (std::chrono::steady_clock::now() - start > std::chrono::duration<double>(seconds)) {
      ::kill(child.pid, SIGKILL);
      ::wait4(child.pid, &status, 0, &usage);
      run.stderr_text = "still running after " + std::to_string(seconds) + " s";
      run.peak_kib = usage.ru_maxrss;
      run.seconds = seconds;
      return run;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.peak_kib = usage.ru_maxrss;
  run.exit_code = decode(status);
  run.stderr_text = child.stderr_text();
  return run;
}

}  // namespace kiln::testing
