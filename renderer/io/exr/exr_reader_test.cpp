#include "io/exr/exr_reader.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "io/exr/exr_file_stream.h"
#include "io/exr/exr_writer.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

fs::path scratch_dir() {
  fs::path dir = fs::temp_directory_path() / ("kiln_exr_reader_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

film small_film() {
  film f(9, 7);
  for (size_t i = 0; i < f.color.size(); ++i) {
    f.color[i] = vec4(0.01f * float(i), 0.5f, 0.25f, 1.0f);
    f.depth[i] = 1.0f + float(i);
    f.vec3_layer(aov::normal)[i] = vec3(0.0f, 0.0f, 1.0f);
  }
  return f;
}

// The error read_exr throws for path; fails the test when it throws none or another type.
error read_error(const fs::path& path) {
  try {
    read_exr(path.string());
  } catch (const error& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << ": not a kiln::error: " << e.what();
    return error(error_kind::render, "", "", "");
  }
  ADD_FAILURE() << path << ": read without an error";
  return error(error_kind::render, "", "", "");
}

void expect_one_line_input_error(const fs::path& path) {
  const error e = read_error(path);
  EXPECT_EQ(e.kind(), error_kind::input) << e.what();
  EXPECT_EQ(e.file(), path.string());
  const std::string line = e.what();
  EXPECT_EQ(line.find('\n'), std::string::npos) << line;
  // The file is named once, by the error itself, not again inside OpenEXR's reason.
  EXPECT_EQ(e.reason().find(path.string()), std::string::npos) << line;
  for (char c : line) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << line;
}

// kiln batch's resume check reads every pixel of an earlier output to find a truncated one, and
// kiln stitch reads its bands: a short file of any layout is bad input naming the file, never a
// crash or an OpenEXR exception escaping.
TEST(exr_reader, truncated_files_are_one_line_input_errors_naming_the_file) {
  for (const bool multipart : {false, true})
    for (const int tile : {0, 4}) {
      exr_settings s;
      s.multipart = multipart;
      s.tile_size = tile;
      const std::string name = std::string(multipart ? "multi" : "single") + "_tile" + std::to_string(tile);
      const fs::path whole = scratch_dir() / (name + ".exr");
      write_exr(whole.string(), small_film(), s, exr_metadata{});
      const exr_image complete = read_exr(whole.string());
      EXPECT_EQ(complete.channel_names.size(), 8u);
      const auto size = fs::file_size(whole);
      for (const uintmax_t length : {uintmax_t(0), uintmax_t(3), uintmax_t(40), size / 2, size - 1}) {
        const fs::path cut = scratch_dir() / (name + "_" + std::to_string(length) + ".exr");
        fs::copy_file(whole, cut, fs::copy_options::overwrite_existing);
        fs::resize_file(cut, length);
        SCOPED_TRACE(cut.string());
        expect_one_line_input_error(cut);
      }
    }
}

TEST(exr_reader, files_that_are_not_exr_are_input_errors) {
  const fs::path text = scratch_dir() / "text.exr";
  std::ofstream(text) << "not an image\n";
  expect_one_line_input_error(text);
  EXPECT_EQ(read_error(text).reason(), "not an OpenEXR file");
  expect_one_line_input_error(scratch_dir() / "missing.exr");
}

// OpenEXR writes a part's offset table from a destructor that swallows exceptions, and the C
// library buffers writes: a full disk may first show when the file is flushed. The stream keeps
// that failure for the writer to report.
TEST(exr_file_stream, a_full_disk_is_reported_even_when_the_failing_write_was_buffered) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const int fd = ::open("/dev/full", O_WRONLY | O_CLOEXEC);
  ASSERT_GE(fd, 0);
  exr_file_stream stream(fd, "/dev/full");
  ASSERT_EQ(stream.error(), "");
  stream.write("0123456789", 10);  // lands in the buffer
  const std::string reason = stream.close();
  EXPECT_NE(reason.find("No space left on device"), std::string::npos) << reason;
  ::close(fd);
}

TEST(exr_file_stream, an_unusable_descriptor_is_reported_before_any_write) {
  exr_file_stream stream(-1, (scratch_dir() / "x.exr").string());
  EXPECT_NE(stream.error().find("cannot open the file"), std::string::npos) << stream.error();
  EXPECT_ANY_THROW(stream.write("x", 1));
  EXPECT_EQ(stream.close(), stream.error());
}

}  // namespace
}  // namespace kiln
