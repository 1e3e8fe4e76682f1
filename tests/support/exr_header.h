// An OpenEXR file's header alone, for tests of what kiln refuses before reading pixels: a scanline
// image of half B G R whose data and display windows claim a size the file does not hold.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kiln::testing {

// The header of a scanline OpenEXR image of width x height half RGB pixels, without its pixels.
inline std::string exr_header_claiming(int width, int height) {
  std::string h("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
  auto attribute = [&h](const std::string& name, const std::string& type, const std::string& value) {
    const uint32_t size = uint32_t(value.size());
    h += name + '\0' + type + '\0' + std::string(reinterpret_cast<const char*>(&size), 4) + value;
  };
  auto ints = [](std::vector<int32_t> v) {
    return std::string(reinterpret_cast<const char*>(v.data()), v.size() * 4);
  };
  std::string channels;
  for (const char* c : {"B", "G", "R"}) channels += std::string(c) + '\0' + ints({1, 0, 1, 1});
  attribute("channels", "chlist", channels + '\0');
  attribute("compression", "compression", std::string(1, '\0'));
  attribute("dataWindow", "box2i", ints({0, 0, width - 1, height - 1}));
  attribute("displayWindow", "box2i", ints({0, 0, width - 1, height - 1}));
  attribute("lineOrder", "lineOrder", std::string(1, '\0'));
  const float one = 1.0f, zero[2] = {0.0f, 0.0f};
  attribute("pixelAspectRatio", "float", std::string(reinterpret_cast<const char*>(&one), 4));
  attribute("screenWindowCenter", "v2f", std::string(reinterpret_cast<const char*>(zero), 8));
  attribute("screenWindowWidth", "float", std::string(reinterpret_cast<const char*>(&one), 4));
  return h + '\0';
}

}  // namespace kiln::testing
