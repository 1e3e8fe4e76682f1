// The batch lock in an output folder others can write to: whatever sits at .kiln-batch.lock that
// kiln did not make (a symbolic link, a hard link, a FIFO, someone's file) is refused and left as it
// was, and so is every file it might point to; a lock file a killed batch left is taken over.
#include "app/output_lock.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

fs::path scratch_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("kiln_output_lock_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir / "out");
  return dir;
}

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Taking the lock on dir/out fails with one input error that names the lock file.
void expect_refused(const fs::path& dir) {
  try {
    const output_folder_lock lock((dir / "out").string(), false);
    FAIL() << "the lock was taken";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::input) << e.what();
    EXPECT_NE(std::string(e.what()).find(output_lock_name), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

const std::string victim_text = "a file the batch's user can write, kept elsewhere\n";

TEST(output_lock, a_symbolic_link_as_the_lock_file_is_refused_and_its_target_kept) {
  const fs::path dir = scratch_dir("symlink");
  write_file(dir / "victim", victim_text);
  fs::create_symlink(dir / "victim", dir / "out" / output_lock_name);
  expect_refused(dir);
  EXPECT_EQ(bytes_of(dir / "victim"), victim_text);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "out" / output_lock_name)));
  // A dangling link creates nothing where it points.
  fs::remove(dir / "out" / output_lock_name);
  fs::create_symlink(dir / "created", dir / "out" / output_lock_name);
  expect_refused(dir);
  EXPECT_FALSE(fs::exists(dir / "created"));
}

TEST(output_lock, a_hard_link_fifo_or_foreign_file_as_the_lock_file_is_refused_and_kept) {
  const fs::path dir = scratch_dir("others");
  const fs::path lock = dir / "out" / output_lock_name;
  write_file(dir / "victim", victim_text);
  fs::create_hard_link(dir / "victim", lock);
  expect_refused(dir);
  EXPECT_EQ(bytes_of(dir / "victim"), victim_text);
  EXPECT_TRUE(fs::exists(lock));
  fs::remove(lock);
  write_file(lock, "someone's notes, not a pid\n");
  expect_refused(dir);
  EXPECT_EQ(bytes_of(lock), "someone's notes, not a pid\n");
  fs::remove(lock);
  ASSERT_EQ(::mkfifo(lock.c_str(), 0644), 0);
  expect_refused(dir);  // and without waiting for a writer
  EXPECT_TRUE(fs::is_fifo(fs::symlink_status(lock)));
}

TEST(output_lock, a_lock_file_a_killed_batch_left_is_taken_and_removed_at_the_end) {
  const fs::path dir = scratch_dir("stale");
  const fs::path lock = dir / "out" / output_lock_name;
  write_file(lock, "999999\n");
  {
    const output_folder_lock held((dir / "out").string(), false);
    EXPECT_EQ(bytes_of(lock), std::to_string(::getpid()) + "\n");
  }
  EXPECT_FALSE(fs::exists(fs::symlink_status(lock)));
}

// A link at the lock file's name is no batch's lock: a render is not refused because of whatever
// holds a lock on the file it points to, and nothing is read through it.
TEST(output_lock, a_symbolic_link_at_the_lock_name_locks_nothing_for_a_render) {
  const fs::path dir = scratch_dir("check");
  write_file(dir / "victim", victim_text);
  const int fd = ::open((dir / "victim").c_str(), O_RDONLY | O_CLOEXEC);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  fs::create_symlink(dir / "victim", dir / "out" / output_lock_name);
  EXPECT_NO_THROW(check_not_in_locked_folder((dir / "out" / "x.exr").string()));
  ::close(fd);
}

// A lock covers its folder's subtree: a folder inside a locked one cannot be locked (a second
// batch there would mix its outputs with the first's), and no lock file is left behind.
TEST(output_lock, a_folder_inside_a_locked_folder_is_refused_until_the_lock_goes) {
  const fs::path dir = scratch_dir("nested");
  const fs::path inner = dir / "out" / "sub" / "deeper";
  fs::create_directories(inner);
  {
    const output_folder_lock held((dir / "out").string(), false);
    try {
      const output_folder_lock nested(inner.string(), false);
      FAIL() << "a folder inside a locked folder was locked";
    } catch (const error& e) {
      EXPECT_EQ(e.kind(), error_kind::input);
      EXPECT_EQ(std::string(e.what()),
                inner.string() + ": the output folder lies inside " + (dir / "out").string() +
                    ", the output folder of another kiln batch (pid " + std::to_string(::getpid()) +
                    ") that is still running; wait for it to finish, give another "
                    "--out-dir, or pass --wait-for-lock");
    }
    EXPECT_FALSE(fs::exists(fs::symlink_status(inner / output_lock_name)));
  }
  EXPECT_NO_THROW(output_folder_lock(inner.string(), false));
}

// A batch's outputs are checked below its own folder only: its own lock is not a refusal, a lock
// on a folder inside it is.
TEST(output_lock, outputs_below_a_batchs_own_folder_meet_only_the_locks_inside_it) {
  const fs::path dir = scratch_dir("below");
  fs::create_directories(dir / "out" / "sub");
  const std::string out = (dir / "out").string();
  {
    const output_folder_lock own(out, false);
    EXPECT_NO_THROW(check_not_in_locked_folder((dir / "out" / "sub" / "a.exr").string(), out));
    EXPECT_THROW(check_not_in_locked_folder((dir / "out" / "sub" / "a.exr").string()), error);
  }
  const output_folder_lock other((dir / "out" / "sub").string(), false);
  EXPECT_THROW(check_not_in_locked_folder((dir / "out" / "sub" / "x" / "a.exr").string(), out), error);
  EXPECT_NO_THROW(check_not_in_locked_folder((dir / "out" / "b.exr").string(), out));
}

}  // namespace
}  // namespace kiln
