// The two hashes a batch resumes by: what cannot change pixels (threads, quiet, output) leaves the
// settings hash (every option's own effect is checked from the table in option_table_test.cpp);
// the input hash follows the asset, its buffer and image files, and the environment map.
#include "job/render_fingerprint.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <utility>

namespace kiln {
namespace {

namespace fs = std::filesystem;

std::string settings_hash(const render_options& o) { return make_fingerprint(o).settings_hash; }

TEST(render_fingerprint, threads_quiet_output_and_command_line_leave_the_settings_hash) {
  render_options base, other;
  other.threads = 3;
  other.quiet = true;
  other.output = "elsewhere.exr";
  other.command_line = "kiln render x";
  other.summary_line = false;
  EXPECT_EQ(settings_hash(other), settings_hash(base));
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

TEST(render_fingerprint, input_hash_follows_the_asset_and_every_file_it_names) {
  const fs::path dir = fs::temp_directory_path() / ("kiln_fingerprint_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  write(dir / "a.gltf",
        R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "geo%20metry.bin", "byteLength": 4}],
            "images": [{"uri": "tex.png"}, {"uri": "data:image/png;base64,AAAA"}]})");
  write(dir / "geo metry.bin", "abcd");
  write(dir / "tex.png", "png1");
  write(dir / "sky.hdr", "sky1");
  render_options o;
  o.input = (dir / "a.gltf").string();
  o.environment = (dir / "sky.hdr").string();
  const std::string first = make_fingerprint(o).input_hash;
  EXPECT_EQ(make_fingerprint(o).input_hash, first);  // the same bytes, the same hash
  write(dir / "geo metry.bin", "abce");
  const std::string after_buffer = make_fingerprint(o).input_hash;
  EXPECT_NE(after_buffer, first);
  write(dir / "tex.png", "png2");
  const std::string after_image = make_fingerprint(o).input_hash;
  EXPECT_NE(after_image, after_buffer);
  write(dir / "sky.hdr", "sky2");
  EXPECT_NE(make_fingerprint(o).input_hash, after_image);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace kiln
