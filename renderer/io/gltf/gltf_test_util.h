// Test helpers for the glTF loader: a per-test temporary folder, small embedded images, the
// one-triangle document most tests start from (built with the tests' one glTF builder,
// tests/support/gltf_builder.h) and a catcher for the error a load throws. Tests only; not part
// of kiln_io_gltf.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "support/gltf_builder.h"

namespace kiln::gltf_test {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::base64_encode;
using testing::gltf_builder;

constexpr int k_byte = 5120, k_ubyte = 5121, k_short = 5122, k_ushort = 5123, k_uint = 5125, k_float = 5126;

// A 2x2 RGBA8 PNG: red, green / blue, white with alpha 128.
constexpr const char* png_2x2_base64 =
    "iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAYAAABytg0kAAAAE0lEQVR4nGP4z8DwHwyBNAg0AABJSQl4KKDbdwAAAABJRU5ErkJggg="
    "=";
// A 1x1 16-bit RGB PNG: (65535, 32768, 0).
constexpr const char* png_16bit_base64 =
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABEAIAAADA54+dAAAAD0lEQVR4nGP4/7+BgYEBAAz8An+jd5TMAAAAAElFTkSuQmCC";

// A fresh folder per test under the system temp folder, removed when the test ends.
class temp_folder {
 public:
  temp_folder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("kiln_gltf_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
             std::to_string(reinterpret_cast<uintptr_t>(this) & 0xffffff));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~temp_folder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  temp_folder(const temp_folder&) = delete;
  temp_folder& operator=(const temp_folder&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

inline void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// A builder holding one triangle mesh (positions + u16 indices) placed by one node.
inline gltf_builder single_triangle() {
  gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int idx = b.add_data(std::vector<uint16_t>{0, 1, 2}, k_ushort, "SCALAR", 1);
  const int mesh = b.add_mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
  b.set_scene({b.add_node({{"mesh", mesh}})});
  return b;
}

// Loads `path` expecting kiln::error; returns its message ("" and a test failure when it loads).
template <typename Load>
std::string error_of(Load load) {
  try {
    load();
  } catch (const kiln::error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected kiln::error, but the file loaded";
  return "";
}

}  // namespace kiln::gltf_test
