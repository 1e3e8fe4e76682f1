// Files a scene or the command line names that are not regular files, or lie outside the asset's
// folder, are refused before a byte of them is read: kiln exits 2 at once with one line naming the
// path and the JSON pointer, where reading would block (a FIFO) or never end (/dev/zero). Each case
// runs under a deadline, so a regression fails instead of hanging the suite. A signal while kiln
// reads a large input stops it with 128 + the signal.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
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

// Generous: each case takes well under a second; a hang (blocked in open() or reading /dev/zero)
// runs into it.
constexpr double deadline_seconds = 20.0;

// One triangle whose vertex buffer is the file at buffer_uri (36 bytes when it is the real one)
// and, when image_uri is given, an image no material uses.
std::string triangle_gltf(const std::string& buffer_uri, uint64_t byte_length = 36,
                          const std::string& image_uri = "") {
  std::string text = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "buffers": [{"uri": ")" +
                     buffer_uri + R"(", "byteLength": )" + std::to_string(byte_length) + "}]";
  if (!image_uri.empty()) text += R"(, "images": [{"uri": ")" + image_uri + R"("}])";
  return text + "}\n";
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A folder with scene.gltf naming buffer_uri (and image_uri), a real geometry.bin beside it.
fs::path scene_folder(const std::string& name, const std::string& buffer_uri,
                      const std::string& image_uri = "") {
  const fs::path dir = scratch_folder(name);
  fs::create_directories(dir / "assets");
  write_text(dir / "assets/scene.gltf", triangle_gltf(buffer_uri, 36, image_uri));
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::ofstream(dir / "assets/geometry.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(positions), sizeof positions);
  return dir;
}

struct outcome {
  std::optional<int> code;  // empty: killed at the deadline
  std::string message;
};

outcome run(const std::vector<std::string>& arguments, const fs::path& dir) {
  const child_process child = start_kiln(arguments, dir.string());
  outcome result;
  result.code = child.wait_at_most(deadline_seconds);
  result.message = child.stderr_text();
  return result;
}

std::vector<std::string> render_args(const fs::path& dir, const std::string& asset,
                                     const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"render",  asset, "-o",       (dir / "out.exr").string(),
                                "--width", "8",   "--height", "8"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

// Exit 2 before the deadline with one line holding every expected fragment; no output written.
void expect_refused(const outcome& result, const fs::path& dir, const std::vector<std::string>& fragments) {
  ASSERT_TRUE(result.code.has_value()) << "kiln hung (killed after " << deadline_seconds << " s)";
  EXPECT_EQ(*result.code, 2) << result.message;
  EXPECT_EQ(lines(result.message).size(), 1u) << result.message;
  for (const std::string& fragment : fragments)
    EXPECT_NE(result.message.find(fragment), std::string::npos)
        << "'" << fragment << "' missing: " << result.message;
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

TEST(input_files, the_triangle_scene_itself_renders) {
  const fs::path dir = scene_folder("good", "geometry.bin");
  const outcome result = run(render_args(dir, (dir / "assets/scene.gltf").string()), dir);
  ASSERT_TRUE(result.code.has_value());
  EXPECT_EQ(*result.code, 0) << result.message;
}

TEST(input_files, absolute_uri_naming_dev_zero_is_refused) {
  const fs::path dir = scene_folder("absolute", "/dev/zero");
  expect_refused(run(render_args(dir, (dir / "assets/scene.gltf").string()), dir), dir,
                 {"scene.gltf", "/buffers/0/uri", "/dev/zero", "absolute path"});
  // Absolute paths are refused even where files outside the folder are allowed.
  expect_refused(run(render_args(dir, (dir / "assets/scene.gltf").string(), {"--allow-outside-files"}), dir),
                 dir, {"/buffers/0/uri", "/dev/zero", "absolute path"});
}

TEST(input_files, dot_dot_escape_to_dev_zero_is_refused) {
  const std::string escape = "../../../../../../../../../../../../dev/zero";
  const fs::path dir = scene_folder("dotdot", escape);
  expect_refused(run(render_args(dir, (dir / "assets/scene.gltf").string()), dir), dir,
                 {"/buffers/0/uri", escape, "outside the asset's folder"});
  // Allowed outside the folder, it is still a device.
  expect_refused(run(render_args(dir, (dir / "assets/scene.gltf").string(), {"--allow-outside-files"}), dir),
                 dir, {"/buffers/0/uri", escape, "is a character device, not a regular file"});
}

TEST(input_files, percent_encoded_escape_in_an_image_uri_is_refused) {
  std::string escape;
  for (int i = 0; i < 12; ++i) escape += "%2e%2e/";
  const fs::path dir = scene_folder("percent", "geometry.bin", escape + "dev/zero");
  expect_refused(run(render_args(dir, (dir / "assets/scene.gltf").string()), dir), dir,
                 {"/images/0/uri", "outside the asset's folder"});
}

TEST(input_files, symlink_to_dev_zero_in_the_folder_is_refused) {
  const fs::path dir = scene_folder("symlink", "zero.bin");
  fs::create_symlink("/dev/zero", dir / "assets/zero.bin");
  expect_refused(run(render_args(dir, (dir / "assets/scene.gltf").string()), dir), dir,
                 {"/buffers/0/uri", "zero.bin", "outside the asset's folder"});
  expect_refused(run(render_args(dir, (dir / "assets/scene.gltf").string(), {"--allow-outside-files"}), dir),
                 dir, {"/buffers/0/uri", "zero.bin", "is a character device, not a regular file"});
}

TEST(input_files, fifo_in_the_folder_is_refused) {
  const fs::path dir = scene_folder("fifo", "geometry.bin", "pipe.png");
  ASSERT_EQ(::mkfifo((dir / "assets/pipe.png").c_str(), 0644), 0);
  expect_refused(run(render_args(dir, (dir / "assets/scene.gltf").string()), dir), dir,
                 {"scene.gltf", "/images/0/uri", "pipe.png", "is a FIFO, not a regular file"});
}

TEST(input_files, asset_that_is_a_fifo_is_refused) {
  const fs::path dir = scratch_folder("asset_fifo");
  ASSERT_EQ(::mkfifo((dir / "scene.gltf").c_str(), 0644), 0);
  expect_refused(run(render_args(dir, (dir / "scene.gltf").string()), dir), dir,
                 {(dir / "scene.gltf").string(), "a FIFO, not a glTF file"});
}

TEST(input_files, environment_that_is_a_device_or_a_fifo_is_refused) {
  const fs::path dir = scene_folder("environment", "geometry.bin");
  const std::string asset = (dir / "assets/scene.gltf").string();
  expect_refused(run(render_args(dir, asset, {"--environment", "/dev/zero"}), dir), dir,
                 {"/dev/zero", "--environment", "is a character device, not a regular file"});
  ASSERT_EQ(::mkfifo((dir / "sky.exr").c_str(), 0644), 0);
  expect_refused(run(render_args(dir, asset, {"--environment", (dir / "sky.exr").string()}), dir), dir,
                 {(dir / "sky.exr").string(), "--environment", "is a FIFO, not a regular file"});
}

// A FIFO among a batch's assets is bad input of the batch itself, like a malformed manifest: refused
// before anything renders (a missing or broken asset, by contrast, fails its job alone).
TEST(input_files, batch_naming_a_fifo_is_refused_before_anything_renders) {
  const fs::path dir = scene_folder("batch", "geometry.bin");
  ASSERT_EQ(::mkfifo((dir / "pipe.gltf").c_str(), 0644), 0);
  const outcome result = run({"batch", (dir / "pipe.gltf").string(), (dir / "assets/scene.gltf").string(),
                              "--out-dir", (dir / "out").string(), "--width", "8", "--height", "8", "-q"},
                             dir);
  ASSERT_TRUE(result.code.has_value()) << "kiln batch hung";
  EXPECT_EQ(*result.code, 2) << result.message;
  EXPECT_NE(result.message.find((dir / "pipe.gltf").string() + " is a FIFO"), std::string::npos)
      << result.message;
  EXPECT_FALSE(fs::exists(dir / "out/scene.exr")) << result.message;
}

TEST(input_files, batch_manifest_that_is_a_fifo_is_refused) {
  const fs::path dir = scratch_folder("manifest_fifo");
  ASSERT_EQ(::mkfifo((dir / "jobs.json").c_str(), 0644), 0);
  expect_refused(
      run({"batch", "--manifest", (dir / "jobs.json").string(), "--out-dir", (dir / "out").string()}, dir),
      dir, {(dir / "jobs.json").string(), "is a FIFO, not a regular file"});
}

// A signal while kiln hashes (or loads) a 200 MB buffer stops it with 143 and a line naming what
// it was reading, instead of finishing the read and the load first.
TEST(input_files, sigterm_while_reading_a_large_buffer_stops_kiln) {
  const fs::path dir = scratch_folder("large_buffer");
  const uint64_t size = uint64_t(200) << 20;
  write_text(dir / "scene.gltf", triangle_gltf("large.bin", size));
  {
    const int fd = ::open((dir / "large.bin").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::ftruncate(fd, off_t(size)), 0);  // sparse: no disk, reads as zeros
    ::close(fd);
  }
  const std::string buffer = fs::canonical(dir / "large.bin").string();
  const child_process child = start_kiln(render_args(dir, (dir / "scene.gltf").string()), dir.string());
  // The moment it has the buffer open, it is reading it.
  bool reading = false;
  for (int i = 0; i < 20000 && !reading; ++i) {
    reading = child.has_open(buffer);
    if (!reading) std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  ASSERT_TRUE(reading) << "kiln never opened the buffer: " << child.stderr_text();
  ASSERT_EQ(::kill(child.pid, SIGTERM), 0);
  const std::optional<int> code = child.wait_at_most(deadline_seconds);
  ASSERT_TRUE(code.has_value()) << "kiln ignored SIGTERM";
  EXPECT_EQ(*code, 128 + SIGTERM) << child.stderr_text();
  const std::vector<std::string> message = lines(child.stderr_text());
  ASSERT_EQ(message.size(), 1u) << child.stderr_text();
  EXPECT_NE(message[0].find("interrupted while reading"), std::string::npos) << message[0];
  EXPECT_NE(message[0].find("large.bin"), std::string::npos) << message[0];
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

}  // namespace
}  // namespace kiln
