// `kiln batch` stopped and locked, through the real binary: SIGTERM or SIGINT stops the batch
// cleanly with 128 + the signal and a summary, and a resumed run finishes it with the pixels of a
// fresh one; a running batch locks its --out-dir against a second batch and a render into it.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "support/batch_cli_files.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::command_result;
using testing::run_kiln;
using testing::scratch_folder;
using namespace batch_testing;

// Jobs of about a second each, so a signal sent when the first output appears lands mid-batch.
void write_slow_manifest(const fs::path& dir) {
  copy_scene(dir / "scenes");
  write_file(dir / "jobs.json", R"({"defaults": {"width": 200, "height": 150, "spp": 24, "threads": 2},
    "jobs": [{"asset": "scenes/cornell_box.gltf", "output": "a.exr"},
             {"asset": "scenes/cornell_box.gltf", "output": "b.exr", "spp": 25},
             {"asset": "scenes/cornell_box.gltf", "output": "c.exr", "spp": 26}]})");
}

// Starts kiln with args in the background, stderr into err_file; returns its pid.
pid_t start_kiln(std::vector<std::string> args, const std::string& err_file) {
  args.insert(args.begin(), KILN_BINARY);
  std::vector<char*> argv;
  for (std::string& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_RDWR);
    const int err = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(null, STDIN_FILENO);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

// Starts the slow batch in dir, sends signo once the first output exists, and checks the exit code
// and the summary: a rendered, b interrupted (or not yet started), c not started.
void expect_signal_stops_batch(const fs::path& dir, int signo) {
  const std::string out = (dir / "out").string(), summary = (dir / "summary.json").string();
  const pid_t pid = start_kiln(
      {"batch", "--manifest", (dir / "jobs.json").string(), "--out-dir", out, "--summary", summary, "-q"},
      "/dev/null");
  ASSERT_GT(pid, 0);
  // The first output appears by rename, so it is complete the moment it exists.
  for (int i = 0; i < 6000 && !fs::exists(out + "/a.exr"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(fs::exists(out + "/a.exr"));
  ASSERT_EQ(::kill(pid, signo), 0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + signo);

  const json stopped = read_json(summary);
  const std::vector<std::string> seen = statuses(stopped);
  EXPECT_EQ(stopped["exit_code"], 128 + signo);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0], "rendered");
  // b was rendering (or, on a slow machine, not yet started) when the signal came; c never starts.
  EXPECT_TRUE(seen[1] == "interrupted" || seen[1] == "not_started") << seen[1];
  EXPECT_EQ(seen[2], "not_started");
  if (seen[1] == "interrupted") {
    EXPECT_NE(stopped["jobs"][1]["error"].get<std::string>().find("interrupted"), std::string::npos);
  }
  EXPECT_EQ(stopped["totals"]["rendered"], 1);
  EXPECT_EQ(stopped["totals"]["not_started"].get<int>() + stopped["totals"]["interrupted"].get<int>(), 2);
}

TEST(batch_cli, sigterm_stops_the_batch_with_exit_143_and_a_summary) {
  const fs::path dir = scratch_folder("batch_sigterm");
  write_slow_manifest(dir);
  expect_signal_stops_batch(dir, SIGTERM);
  EXPECT_EQ(files_in(dir / "out"), (std::vector<std::string>{"a.exr"}));
}

TEST(batch_cli, sigint_stops_the_batch_cleanly_and_resume_finishes_it_like_a_fresh_run) {
  const fs::path dir = scratch_folder("batch_sigint");
  write_slow_manifest(dir);
  expect_signal_stops_batch(dir, SIGINT);
  if (HasFatalFailure()) return;
  const std::string out = (dir / "out").string(), summary = (dir / "summary.json").string();
  // Only the finished output: no partial b.exr, no temporary file.
  EXPECT_EQ(files_in(out), (std::vector<std::string>{"a.exr"}));
  const auto a_id = identity(out + "/a.exr");

  const command_result resumed = run_kiln({"batch", "--manifest", (dir / "jobs.json").string(), "--out-dir",
                                           out, "--summary", summary, "--resume", "-q"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.stderr_text;
  EXPECT_EQ(statuses(read_json(summary)), (std::vector<std::string>{"skipped", "rendered", "rendered"}));
  EXPECT_EQ(identity(out + "/a.exr"), a_id);

  const std::string fresh = (dir / "fresh").string();
  const command_result clean =
      run_kiln({"batch", "--manifest", (dir / "jobs.json").string(), "--out-dir", fresh, "-q"});
  ASSERT_EQ(clean.exit_code, 0) << clean.stderr_text;
  for (const char* name : {"/a.exr", "/b.exr", "/c.exr"}) expect_same_pixels(out + name, fresh + name);
}

int wait_exit_code(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// True while some process holds an exclusive flock on path.
bool locked(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return false;
  const bool busy = ::flock(fd, LOCK_SH | LOCK_NB) != 0;
  ::close(fd);
  return busy;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A running batch locks its --out-dir: a second batch on it is refused with exit 2 (or waits with
// --wait-for-lock, then runs), and so is a render into it; the lock file goes when the batch ends.
TEST(batch_cli, a_second_batch_or_a_render_into_a_running_batchs_folder_is_refused) {
  const fs::path dir = scratch_folder("batch_lock");
  write_slow_manifest(dir);
  const std::string out = (dir / "out").string(), lock = out + "/.kiln-batch.lock";
  const pid_t slow = start_kiln({"batch", "--manifest", (dir / "jobs.json").string(), "--out-dir", out, "-q"},
                                (dir / "slow.err").string());
  ASSERT_GT(slow, 0);
  for (int i = 0; i < 6000 && !locked(lock); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(locked(lock));

  const std::string asset = (dir / "scenes/cornell_box.gltf").string();
  const command_result second =
      run_kiln(batch_args({asset, "--out-dir", out, "--summary", (dir / "second.json").string()}));
  EXPECT_EQ(second.exit_code, 2) << second.stderr_text;
  EXPECT_EQ(second.stderr_text,
            "kiln: " + out + ": the output folder is in use by another kiln batch (pid " +
                std::to_string(slow) +
                "); wait for it to finish, give another --out-dir, or pass --wait-for-lock\n");
  EXPECT_FALSE(fs::exists(dir / "second.json"));
  for (const std::string& target : {out + "/cornell_box.exr", out + "/sub/deeper/x.exr"}) {
    const command_result render =
        run_kiln({"render", asset, "-o", target, "--width", "8", "--height", "8", "-q"});
    EXPECT_EQ(render.exit_code, 2) << render.stderr_text;
    EXPECT_NE(render.stderr_text.find(target + ": the folder " + out +
                                      " is the output folder of another kiln batch (pid " +
                                      std::to_string(slow) + ")"),
              std::string::npos)
        << render.stderr_text;
    EXPECT_FALSE(fs::exists(target));
  }
  // A render elsewhere is not affected.
  EXPECT_EQ(run_kiln({"render", asset, "-o", (dir / "elsewhere.exr").string(), "--width", "8", "--height",
                      "8", "-q"})
                .exit_code,
            0);

  // --wait-for-lock waits for the first batch (stopped here by SIGTERM) and then renders.
  const pid_t waiting = start_kiln(
      batch_args({asset, "--out-dir", out, "--wait-for-lock", "--summary", (dir / "waited.json").string()}),
      (dir / "waiting.err").string());
  for (int i = 0; i < 2000 && read_text((dir / "waiting.err").string()).empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(read_text((dir / "waiting.err").string()), "kiln batch: waiting for another kiln batch (pid " +
                                                           std::to_string(slow) + ") to release " + out +
                                                           "\n");
  EXPECT_FALSE(fs::exists(dir / "waited.json"));
  ASSERT_EQ(::kill(slow, SIGTERM), 0);
  EXPECT_EQ(wait_exit_code(slow), 128 + SIGTERM);
  EXPECT_EQ(wait_exit_code(waiting), 0) << read_text((dir / "waiting.err").string());
  EXPECT_EQ(statuses(read_json(dir / "waited.json")), (std::vector<std::string>{"rendered"}));
  EXPECT_FALSE(fs::exists(lock));  // removed by whoever held it last
}

}  // namespace
}  // namespace kiln
