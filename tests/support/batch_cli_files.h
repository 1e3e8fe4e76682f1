// What the end-to-end tests of `kiln batch` share: the demo scene copied, files written and read
// back (JSON summaries, EXR pixels bit for bit, a file's inode and modification time), and the
// `kiln batch` arguments of a tiny job. Header only, for tests that link OpenImageIO and JSON.
#pragma once

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "support/run_kiln.h"

namespace kiln::batch_testing {

namespace fs = std::filesystem;
using json = nlohmann::json;

inline std::string copy_scene(const fs::path& folder, const std::string& name = "cornell_box.gltf") {
  return testing::copy_scene(folder.string(), name);
}

inline void write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

inline json read_json(const fs::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << path;
  return json::parse(in);
}

struct image {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;  // every channel as float: exact for half and float
};

inline image read_image(const std::string& path) {
  image out;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  if (!in) return out;
  out.spec = in->spec();
  out.pixels.resize(out.spec.image_pixels() * size_t(out.spec.nchannels));
  EXPECT_TRUE(in->read_image(0, 0, 0, out.spec.nchannels, OIIO::TypeDesc::FLOAT, out.pixels.data())) << path;
  return out;
}

inline std::string attribute(const image& i, const std::string& name) {
  return i.spec.get_string_attribute(name);
}

// Same size, channels (names and formats) and pixel values, bit for bit.
inline void expect_same_pixels(const std::string& a_path, const std::string& b_path) {
  const image a = read_image(a_path), b = read_image(b_path);
  EXPECT_EQ(a.spec.width, b.spec.width);
  EXPECT_EQ(a.spec.height, b.spec.height);
  EXPECT_EQ(a.spec.channelnames, b.spec.channelnames);
  EXPECT_EQ(a.spec.channelformats, b.spec.channelformats);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0)
      << a_path << " and " << b_path << " differ";
}

// Inode and modification time: a skipped output keeps both, a rewritten one (renamed into place) gets a new
// inode.
inline std::pair<ino_t, int64_t> identity(const std::string& path) {
  struct stat s {};
  EXPECT_EQ(::stat(path.c_str(), &s), 0) << path;
  return {s.st_ino, int64_t(s.st_mtim.tv_sec) * 1000000000 + s.st_mtim.tv_nsec};
}

inline std::vector<std::string> statuses(const json& summary) {
  std::vector<std::string> out;
  for (const json& job : summary["jobs"]) out.push_back(job["status"]);
  return out;
}

inline std::vector<std::string> files_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file()) names.push_back(fs::relative(entry.path(), folder).string());
  std::sort(names.begin(), names.end());
  return names;
}

inline const std::vector<std::string> tiny = {"--width", "24", "--height", "18"};

inline std::vector<std::string> batch_args(std::vector<std::string> args,
                                           const std::vector<std::string>& extra = tiny) {
  args.insert(args.begin(), "batch");
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

}  // namespace kiln::batch_testing
