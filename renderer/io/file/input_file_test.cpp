// The input-file reader refuses what is not a regular file before reading (a FIFO without a
// writer, a device, a folder, a link to a device), refuses files over the limit, stops at a
// raised cancel flag, and reads a regular file whole.
#include "io/file/input_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("kiln_input_file_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The error reading path throws, or an empty optional-like marker when it reads.
error refusal_of(const std::string& path, const input_file_request& request) {
  try {
    read_whole_input_file(path, request);
  } catch (const error& e) {
    return e;
  }
  return error(error_kind::render, "", "", "no error");
}

TEST(input_file, reads_a_regular_file_whole) {
  const fs::path dir = scratch("regular");
  std::ofstream(dir / "a.bin", std::ios::binary) << "abcdef";
  const std::vector<uint8_t> bytes = read_whole_input_file((dir / "a.bin").string(), {1024});
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "abcdef");
  EXPECT_EQ(input_file_problem((dir / "a.bin").string(), 1024), "");
}

TEST(input_file, refuses_what_is_not_a_regular_file_without_blocking) {
  const fs::path dir = scratch("special");
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0644), 0);
  fs::create_symlink("/dev/zero", dir / "zero_link");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {(dir / "fifo").string(), "is a FIFO, not a regular file"},
      {"/dev/zero", "is a character device, not a regular file"},
      {(dir / "zero_link").string(), "is a character device, not a regular file"},
      {dir.string(), "is a folder, not a regular file"}};
  for (const auto& [path, reason] : cases) {
    EXPECT_EQ(input_file_problem(path, 1024), reason) << path;
    const error e = refusal_of(path, {1024});
    EXPECT_EQ(e.kind(), error_kind::input) << path;
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.reason(), reason) << path;
  }
}

TEST(input_file, names_the_asset_and_pointer_that_led_to_the_file) {
  const fs::path dir = scratch("named");
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0644), 0);
  const error e = refusal_of((dir / "fifo").string(), {1024, nullptr, "scene.gltf", "/buffers/0/uri"});
  EXPECT_EQ(e.kind(), error_kind::input);
  EXPECT_EQ(std::string(e.what()),
            "scene.gltf: /buffers/0/uri: '" + (dir / "fifo").string() + "' is a FIFO, not a regular file");
}

TEST(input_file, refuses_a_file_over_the_limit_and_a_missing_one) {
  const fs::path dir = scratch("limits");
  std::ofstream(dir / "big.bin", std::ios::binary) << std::string(100, 'x');
  EXPECT_EQ(input_file_problem((dir / "big.bin").string(), 99), "is 100 bytes, over kiln's limit of 99");
  EXPECT_EQ(refusal_of((dir / "big.bin").string(), {99}).kind(), error_kind::input);
  EXPECT_EQ(read_whole_input_file((dir / "big.bin").string(), {100}).size(), 100u);
  EXPECT_TRUE(input_file_missing((dir / "none.bin").string()));
  EXPECT_FALSE(input_file_missing((dir / "big.bin").string()));
  const error missing = refusal_of((dir / "none.bin").string(), {100});
  EXPECT_EQ(missing.kind(), error_kind::input);
  EXPECT_NE(missing.reason().find("cannot open file"), std::string::npos) << missing.what();
}

TEST(input_file, stops_when_the_cancel_flag_is_raised) {
  const fs::path dir = scratch("cancel");
  {
    std::ofstream out(dir / "large.bin", std::ios::binary);
    out << std::string(size_t(8) << 20, 'x');  // eight chunks
  }
  std::atomic<bool> cancel{false};
  size_t seen = 0;
  try {
    read_input_file((dir / "large.bin").string(), {uint64_t(1) << 30, &cancel},
                    [&](const char*, size_t count) {
                      seen += count;
                      cancel = true;  // as a signal handler would, during the first chunk
                    });
    FAIL() << "the read did not stop";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::interrupted);
    EXPECT_NE(std::string(e.what()).find("large.bin"), std::string::npos) << e.what();
  }
  EXPECT_EQ(seen, size_t(1) << 20) << "read on after the flag was raised";
}

}  // namespace
}  // namespace kiln
