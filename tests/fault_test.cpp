// Faults from outside the renderer: signals during a render, a full disk, and outputs that are not
// files. In every case kiln exits non-zero with one line, leaves no temporary file, and never
// touches an output that already existed.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>

#include "support/kiln_process.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using testing::child_process;
using testing::lines;
using testing::scratch_folder;
using testing::start_kiln;

const std::string demo_scene = std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf";
const std::string previous_content = "an earlier render that must survive\n";

void write_file(const std::string& path, const std::string& content) { std::ofstream(path) << content; }

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Files in folder other than the test's own stderr capture and the pre-existing output.
std::vector<std::string> stray_files(const std::string& folder, const std::string& keep) {
  std::vector<std::string> stray;
  for (const auto& entry : fs::directory_iterator(folder)) {
    std::string name = entry.path().filename().string();
    if (name != "stderr.txt" && name != keep) stray.push_back(name);
  }
  return stray;
}

// A render that takes many seconds, so a signal always arrives mid-render.
std::vector<std::string> long_render(const std::string& output) {
  return {"render",   demo_scene, "-o",    output, "--width",   "1920",
          "--height", "1440",     "--spp", "1024", "--threads", "2"};
}

// Few pixels of a huge number of samples in one tile: each pixel takes long, so a check per tile
// row or per pixel alone would keep the signal waiting for seconds.
std::vector<std::string> long_pixels_render(const std::string& output) {
  return {"render", demo_scene, "-o",    output,        "--width", "512",       "--height",
          "512",    "--spp",    "65536", "--tile-size", "512",     "--threads", "2"};
}

void expect_signal_stops_render(
    int signo, const std::function<std::vector<std::string>(const std::string&)>& args = long_render) {
  std::string folder = scratch_folder("signal_" + std::to_string(signo));
  std::string output = folder + "/frame.exr";
  write_file(output, previous_content);
  child_process child = start_kiln(args(output), folder);
  // Wait until kiln handles the signal (a loaded machine may take a while to start it), then
  // give it time to load the scene and start tracing.
  for (int i = 0; i < 1000 && !child.catches(signo); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(child.catches(signo)) << "kiln never installed a handler for signal " << signo;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  auto sent = std::chrono::steady_clock::now();
  ASSERT_EQ(::kill(child.pid, signo), 0);
  int code = child.wait();
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();

  EXPECT_EQ(code, 128 + signo) << child.stderr_text();
  EXPECT_LT(seconds, 1.0) << "kiln took " << seconds << " s to stop";
  std::vector<std::string> message = lines(child.stderr_text());
  ASSERT_FALSE(message.empty());
  EXPECT_NE(message.back().find("interrupted"), std::string::npos) << message.back();
  EXPECT_NE(message.back().find(output), std::string::npos) << message.back();
  EXPECT_EQ(read_file(output), previous_content) << "the earlier output was touched";
  EXPECT_TRUE(stray_files(folder, "frame.exr").empty()) << "a temporary file was left behind";
}

TEST(faults, sigint_stops_the_render_within_a_second_and_writes_nothing) {
  expect_signal_stops_render(SIGINT);
}

TEST(faults, sigterm_stops_the_render_within_a_second_and_writes_nothing) {
  expect_signal_stops_render(SIGTERM);
}

TEST(faults, sigint_stops_a_render_of_65536_samples_a_pixel_within_a_second) {
  expect_signal_stops_render(SIGINT, long_pixels_render);
}

// Writing 800x800 one-pixel tiles takes seconds: long enough to signal kiln mid-write.
std::vector<std::string> long_write(const std::string& output) {
  return {"render", demo_scene, "-o",     output,      "--width", "800", "--height", "800", "--exr-tile-size",
          "1",      "--aovs",   "beauty", "--threads", "2",       "-q",  "--spp",    "1"};
}

// The temporary file kiln writes beside output (".frame.exr.kiln-tmp-HOST-PID-N"), once it exists.
std::string wait_for_temporary(const std::string& folder) {
  for (int i = 0; i < 6000; ++i) {
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.path().filename().string().rfind(".frame.exr.kiln-tmp-", 0) == 0)
        return entry.path().string();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return "";
}

TEST(faults, sigterm_during_the_exr_write_stops_it_and_keeps_the_earlier_output) {
  const std::string folder = scratch_folder("signal_during_write");
  const std::string output = folder + "/frame.exr";
  write_file(output, previous_content);
  child_process child = start_kiln(long_write(output), folder);
  ASSERT_FALSE(wait_for_temporary(folder).empty()) << child.stderr_text();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const auto sent = std::chrono::steady_clock::now();
  ASSERT_EQ(::kill(child.pid, SIGTERM), 0);
  const std::optional<int> code = child.wait_at_most(60);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 128 + SIGTERM) << child.stderr_text();
  EXPECT_LT(seconds, 2.0) << "kiln kept writing for " << seconds << " s";
  const std::vector<std::string> message = lines(child.stderr_text());
  ASSERT_EQ(message.size(), 1u) << child.stderr_text();
  EXPECT_NE(message[0].find(output + ": interrupted while writing, nothing written"), std::string::npos);
  EXPECT_EQ(read_file(output), previous_content);
  EXPECT_TRUE(stray_files(folder, "frame.exr").empty()) << "a temporary file was left behind";
}

// A second signal kills kiln at once (the default action), and still no temporary file is left.
TEST(faults, two_signals_during_the_exr_write_leave_no_temporary_file) {
  const std::string folder = scratch_folder("two_signals_during_write");
  const std::string output = folder + "/frame.exr";
  write_file(output, previous_content);
  // Once the temporary file exists the handler is long installed: the first signal asks kiln to
  // stop, the second kills it.
  child_process child = start_kiln(long_write(output), folder);
  ASSERT_FALSE(wait_for_temporary(folder).empty()) << child.stderr_text();
  ASSERT_EQ(::kill(child.pid, SIGTERM), 0);
  ASSERT_EQ(::kill(child.pid, SIGTERM), 0);
  const std::optional<int> code = child.wait_at_most(60);
  ASSERT_TRUE(code.has_value());
  EXPECT_TRUE(*code == -SIGTERM || *code == 128 + SIGTERM) << *code;
  EXPECT_EQ(read_file(output), previous_content);
  EXPECT_TRUE(stray_files(folder, "frame.exr").empty()) << "a temporary file was left behind";
}

// SIGKILL cannot be handled: its temporary file stays, and the next write of that output removes
// it (its process is gone), while a live process's temporary file is left alone, and so is
// everything a write of another output finds.
TEST(faults, the_next_write_removes_what_a_killed_write_left) {
  const std::string folder = scratch_folder("killed_during_write");
  const std::string output = folder + "/frame.exr";
  child_process child = start_kiln(long_write(output), folder);
  const std::string left = wait_for_temporary(folder);
  ASSERT_FALSE(left.empty()) << child.stderr_text();
  ASSERT_EQ(::kill(child.pid, SIGKILL), 0);
  EXPECT_EQ(child.wait(), -SIGKILL);
  ASSERT_TRUE(fs::exists(left));
  // A temporary file of a process that is alive (this test): ".frame.exr.kiln-tmp-HOST-" + its pid.
  const std::string before_pid = left.substr(0, left.rfind('-'));
  const std::string alive =
      before_pid.substr(0, before_pid.rfind('-') + 1) + std::to_string(::getpid()) + "-0";
  write_file(alive, "being written");
  auto result = testing::run_kiln({"render", demo_scene, "-o", folder + "/other.exr", "--width", "8", "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_TRUE(fs::exists(left)) << "a write of other.exr removed " << left;
  result = testing::run_kiln({"render", demo_scene, "-o", output, "--width", "8", "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_FALSE(fs::exists(left)) << left;
  EXPECT_TRUE(fs::exists(alive));
  fs::remove(alive);
}

TEST(faults, full_disk_fails_cleanly_and_keeps_the_earlier_output) {
  std::string folder = scratch_folder("full_disk");
  std::string output = folder + "/frame.exr";
  write_file(output, previous_content);
  // A file-size limit of 4 KiB makes every write past it fail with EFBIG, as a full disk does
  // with ENOSPC; SIGXFSZ is ignored so the write reports the error instead of killing kiln.
  child_process child = start_kiln({"render", demo_scene, "-o", output, "--width", "160", "-q"}, folder, [] {
    std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
  });
  int code = child.wait();
  EXPECT_EQ(code, 1) << child.stderr_text();
  std::vector<std::string> message = lines(child.stderr_text());
  ASSERT_EQ(message.size(), 1u) << child.stderr_text();
  EXPECT_NE(message[0].find(output), std::string::npos) << message[0];
  EXPECT_EQ(read_file(output), previous_content);
  EXPECT_TRUE(stray_files(folder, "frame.exr").empty()) << "a partial temporary file was left behind";
}

// A preview that meets a full disk fails the render (exit 1, one line naming it) and leaves no
// truncated PNG, the earlier preview kept. The limit sits between the EXR's size and the PNG's,
// both measured by a first render, so only the preview's write runs out of room.
TEST(faults, a_preview_on_a_full_disk_fails_and_leaves_no_truncated_file) {
  const std::string folder = scratch_folder("full_disk_preview");
  const std::vector<std::string> args = {"render",
                                         demo_scene,
                                         "-o",
                                         folder + "/frame.exr",
                                         "--width",
                                         "320",
                                         "--aovs",
                                         "beauty",
                                         "--compression",
                                         "dwab",
                                         "-q",
                                         "--preview",
                                         folder + "/frame.png"};
  ASSERT_EQ(testing::run_kiln(args).exit_code, 0);
  const uintmax_t exr = fs::file_size(folder + "/frame.exr"), png = fs::file_size(folder + "/frame.png");
  ASSERT_GT(png, exr + 2048) << "the preview must be the larger file for this test";
  write_file(folder + "/frame.png", previous_content);
  const rlim_t room = rlim_t((exr + png) / 2);
  child_process child = start_kiln(args, folder, [room] {
    std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit{room, room};
    ::setrlimit(RLIMIT_FSIZE, &limit);
  });
  EXPECT_EQ(child.wait(), 1) << child.stderr_text();
  const std::vector<std::string> message = lines(child.stderr_text());
  ASSERT_EQ(message.size(), 1u) << child.stderr_text();
  EXPECT_NE(message[0].find(folder + "/frame.png: cannot write png"), std::string::npos) << message[0];
  EXPECT_EQ(read_file(folder + "/frame.png"), previous_content);
  for (const std::string& name : stray_files(folder, "frame.png"))
    EXPECT_EQ(name, "frame.exr") << "a partial temporary file was left behind";
}

TEST(faults, output_that_is_not_a_regular_file_is_refused_before_rendering) {
  // Writing "to" a pipe or device would replace the node by rename; kiln refuses instead.
  const std::string pipe = scratch_folder("pipe_output") + "/pipe.exr";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0644), 0);
  auto result = testing::run_kiln({"render", demo_scene, "-o", pipe, "--width", "32"});
  EXPECT_EQ(result.exit_code, 1);
  ASSERT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("not a regular file"), std::string::npos) << result.stderr_text;
  EXPECT_TRUE(fs::is_fifo(pipe));
  // A device has no .exr name: a usage error before that check.
  result = testing::run_kiln({"render", demo_scene, "-o", "/dev/null", "--width", "32"});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

// An existing folder where nothing can be created: as root, access() says it is writable, so only
// a real attempt tells. The refusal comes before the render (its wording is the pre-check's).
TEST(faults, output_in_a_folder_that_cannot_hold_files_is_refused_before_rendering) {
  for (const std::string folder : {"/proc", "/sys"}) {
    const std::string output = folder + "/kiln_fault_test.exr";
    auto result = testing::run_kiln({"render", demo_scene, "-o", output, "--width", "1920", "--spp", "1024"});
    EXPECT_EQ(result.exit_code, 1) << result.stderr_text;
    ASSERT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find(output), std::string::npos) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find("output folder is not writable: " + folder), std::string::npos)
        << result.stderr_text;
    EXPECT_FALSE(fs::exists(output));
  }
}

}  // namespace
}  // namespace kiln
