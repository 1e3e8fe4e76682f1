// kiln in an output folder that others can write to, end to end through the binary: a batch lock
// file planted as a symbolic link is refused with one line and exit 2 (the file it points to keeps
// its bytes), and a render removes no file but its own killed writes' temporary files.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// This host as kiln names it in temporary files: anything but [A-Za-z0-9._] becomes '_'.
std::string host() {
  char name[256] = {};
  ::gethostname(name, sizeof name - 1);
  std::string out(name);
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_') c = '_';
  return out.empty() ? "host" : out;
}

// The id of a process that has ended (a child, reaped): no process has it now.
pid_t dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

const std::string victim_text = "a file the batch's user can write, kept outside the output folder\n";

TEST(shared_folder, a_batch_refuses_a_lock_file_that_is_a_symbolic_link_and_keeps_its_target) {
  const fs::path dir = scratch_folder("shared_lock_symlink");
  const std::string asset = testing::copy_scene((dir / "scene").string());
  fs::create_directories(dir / "out");
  write_file(dir / "victim", victim_text);
  const fs::path lock = dir / "out" / ".kiln-batch.lock";
  fs::create_symlink(dir / "victim", lock);
  const auto result =
      run_kiln({"batch", asset, "--out-dir", (dir / "out").string(), "--width", "8", "--height", "6", "-q"});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  ASSERT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find(lock.string() + ": "), std::string::npos) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("symbolic link"), std::string::npos) << result.stderr_text;
  EXPECT_EQ(bytes_of(dir / "victim"), victim_text);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(lock)));
  EXPECT_FALSE(fs::exists(dir / "out" / "cornell_box.exr"));
}

// ".notes.tmp-HOST-PID" of a process that is gone looks like what a killed write of "notes" left,
// but kiln is writing frame.exr: the file is not kiln's to remove.
TEST(shared_folder, a_render_removes_no_file_it_cannot_prove_its_own) {
  const fs::path dir = scratch_folder("shared_sweep");
  const std::string asset = testing::copy_scene((dir / "scene").string());
  const std::string dead = std::to_string(dead_pid());
  const std::vector<std::string> names = {".notes.tmp-" + host() + "-" + dead,
                                          ".other.exr.tmp-" + host() + "-" + dead};
  for (const std::string& name : names) write_file(dir / name, "kept: " + name);
  const auto result =
      run_kiln({"render", asset, "-o", (dir / "frame.exr").string(), "--width", "8", "--height", "6", "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  for (const std::string& name : names) EXPECT_EQ(bytes_of(dir / name), "kept: " + name) << name;
}

}  // namespace
}  // namespace kiln
