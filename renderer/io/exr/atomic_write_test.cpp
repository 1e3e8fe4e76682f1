// The atomic writer in a folder others share: writes of one path from several threads each leave a
// complete file, and the sweep of files killed writes left removes only this writer's own.
#include "io/exr/atomic_write.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <thread>
#include <vector>

#include "core/error.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

fs::path scratch_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("kiln_atomic_write_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Writes text through write_atomically, in pieces, so that writers sharing a file would interleave.
void write_text(const std::string& path, const std::string& text) {
  write_atomically(path, "text", [&](const temporary_file& temporary) -> std::string {
    for (size_t at = 0; at < text.size(); at += 4096) {
      const std::string reason =
          write_all(temporary.fd, text.data() + at, std::min<size_t>(4096, text.size() - at));
      if (!reason.empty()) return reason;
    }
    return "";
  });
}

// This host as the writer names it in temporary files: anything but [A-Za-z0-9._] becomes '_'.
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

// Four threads write one path at once, many times over: every call succeeds, and the file left is
// always exactly one of the complete texts (no two writers ever share a temporary file).
TEST(atomic_write, concurrent_writes_of_one_path_leave_exactly_one_complete_result) {
  const fs::path dir = scratch_dir("concurrent");
  const std::string path = (dir / "out.exr").string();
  std::vector<std::string> texts;
  for (int t = 0; t < 4; ++t) texts.push_back(std::string(256 * 1024 + t, char('a' + t)));
  const std::set<std::string> complete(texts.begin(), texts.end());
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::string> failures(texts.size());
    std::vector<std::thread> writers;
    for (size_t t = 0; t < texts.size(); ++t)
      writers.emplace_back([&, t] {
        try {
          write_text(path, texts[t]);
        } catch (const error& e) {
          failures[t] = e.what();
        }
      });
    for (std::thread& w : writers) w.join();
    for (const std::string& failure : failures) EXPECT_EQ(failure, "") << "trial " << trial;
    ASSERT_EQ(complete.count(bytes_of(path)), 1u) << "trial " << trial << ": the file is no complete result";
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1)
      << "a temporary file was left behind";
}

// Files that only look like a killed writer's temporary file are not kiln's to remove: another
// name's (a user's ".notes.tmp-HOST-PID", another output's), or anything not a regular file.
TEST(atomic_write, the_sweep_spares_files_it_cannot_prove_its_own) {
  const fs::path dir = scratch_dir("sweep");
  const std::string dead = std::to_string(dead_pid());
  const std::vector<std::string> spared = {".notes.tmp-" + host() + "-" + dead,
                                           ".other.exr.tmp-" + host() + "-" + dead,
                                           ".out.exr.backup.tmp-" + host() + "-" + dead};
  for (const std::string& name : spared) write_file(dir / name, "someone's " + name);
  write_text((dir / "out.exr").string(), "the output");
  EXPECT_EQ(bytes_of(dir / "out.exr"), "the output");
  for (const std::string& name : spared) EXPECT_EQ(bytes_of(dir / name), "someone's " + name) << name;
}

// What a killed write of this very output left (its exact name, a dead process of this host, a
// regular file) goes; a live process's file, a link at such a name, and a file of a killed write
// of another output stay.
TEST(atomic_write, the_sweep_removes_what_killed_writes_of_the_output_left) {
  const fs::path dir = scratch_dir("sweep_own");
  const std::string prefix = ".out.exr.kiln-tmp-" + host() + "-", dead = std::to_string(dead_pid());
  write_file(dir / (prefix + dead + "-0"), "left by a killed write");
  write_file(dir / (prefix + dead + "-17"), "left by a killed write");
  write_file(dir / "victim", "kept");
  const std::vector<std::string> spared = {prefix + std::to_string(::getppid()) + "-0", prefix + dead + "-1",
                                           ".other.exr.kiln-tmp-" + host() + "-" + dead + "-0"};
  write_file(dir / spared[0], "being written");
  fs::create_symlink(dir / "victim", dir / spared[1]);
  write_file(dir / spared[2], "another output's");
  write_text((dir / "out.exr").string(), "the output");
  EXPECT_FALSE(fs::exists(dir / (prefix + dead + "-0")));
  EXPECT_FALSE(fs::exists(dir / (prefix + dead + "-17")));
  for (const std::string& name : spared) EXPECT_TRUE(fs::exists(fs::symlink_status(dir / name))) << name;
  EXPECT_EQ(bytes_of(dir / "victim"), "kept");
}

// Older kiln named the temporary file of a write ".NAME.tmp-HOST-PID", one per process: a killed
// write of this very output in that name goes too, by the same rules, and nothing else that
// merely looks like it.
TEST(atomic_write, the_sweep_removes_what_killed_writes_of_older_kiln_left) {
  const fs::path dir = scratch_dir("sweep_legacy");
  const std::string prefix = ".out.exr.tmp-" + host() + "-", dead = std::to_string(dead_pid());
  write_file(dir / (prefix + dead), "left by a killed older kiln");
  write_file(dir / "victim", "kept");
  const std::vector<std::string> spared = {prefix + std::to_string(::getppid()), prefix + dead + "-0",
                                           prefix + dead + "x", ".out.exr.tmp-elsewhere-" + dead,
                                           ".out.exr.tmp-" + dead};
  for (const std::string& name : spared) write_file(dir / name, "someone's " + name);
  write_text((dir / "out.exr").string(), "the output");
  EXPECT_FALSE(fs::exists(dir / (prefix + dead)));
  for (const std::string& name : spared) EXPECT_EQ(bytes_of(dir / name), "someone's " + name) << name;
  // A link at the name is not a file kiln wrote: it stays, and so does what it points to.
  fs::create_symlink(dir / "victim", dir / (prefix + dead));
  write_text((dir / "out.exr").string(), "the output again");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / (prefix + dead))));
  EXPECT_EQ(bytes_of(dir / "victim"), "kept");
}

// A file or link someone placed at the name the next temporary file would take is neither written
// through nor replaced: the write takes another name.
TEST(atomic_write, a_name_taken_in_advance_is_skipped_not_written_through) {
  const fs::path dir = scratch_dir("taken");
  write_file(dir / "victim", "kept");
  std::string probe;
  const int fd = create_temporary_file((dir / "out.exr").string(), probe);
  ASSERT_GE(fd, 0);
  ::close(fd);
  fs::remove(probe);
  // The counter moves on after each name, so the next names are the probe's number + 1, 2, ...
  const std::string stem = probe.substr(0, probe.rfind('-') + 1);
  const long next = std::stol(probe.substr(probe.rfind('-') + 1)) + 1;
  for (long n = next; n < next + 4; ++n) fs::create_symlink(dir / "victim", stem + std::to_string(n));
  write_text((dir / "out.exr").string(), "the output");
  EXPECT_EQ(bytes_of(dir / "out.exr"), "the output");
  EXPECT_EQ(bytes_of(dir / "victim"), "kept");
  for (long n = next; n < next + 4; ++n)
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(stem + std::to_string(n))));
}

}  // namespace
}  // namespace kiln
