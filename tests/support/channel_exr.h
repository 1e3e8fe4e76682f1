// An EXR rendered by the kiln binary and read back with every channel as float, looked up by
// channel name, for the end-to-end AOV tests. Depends on OpenImageIO, GoogleTest and run_kiln.
#pragma once

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "support/float_exr.h"
#include "support/run_kiln.h"

namespace kiln::testing {

struct channel_exr : float_exr {
  // Channel `channel` of pixel `pixel` (raster order); NaN, and a test failure, when it is missing.
  float at(size_t pixel, const std::string& channel) const {
    const int c = spec.channelindex(channel);
    EXPECT_GE(c, 0) << channel;
    return c < 0 ? NAN : pixels[pixel * size_t(spec.nchannels) + size_t(c)];
  }
  bool has(const std::string& channel) const { return spec.channelindex(channel) >= 0; }
  size_t count() const { return spec.image_pixels(); }
};

// `kiln render scene -o path` at width × height, quiet, 32-bit float, with extra options; fails the
// calling test when kiln does not exit 0.
inline channel_exr render_float_exr(const std::string& scene, const std::string& path, int width, int height,
                                    const std::vector<std::string>& extra) {
  std::vector<std::string> args = {
      "render", scene,    "-o", path, "--width", std::to_string(width), "--height", std::to_string(height),
      "-q",     "--float"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto result = run_kiln(args);
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  return channel_exr{read_float_exr(path)};
}

// The part names of a (multi-part) EXR; a test failure, and none, when it cannot be opened.
inline std::set<std::string> exr_part_names_in(const std::string& path) {
  std::set<std::string> parts;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  for (int part = 0; in && in->seek_subimage(part, 0); ++part)
    parts.insert(in->spec().get_string_attribute("name"));
  return parts;
}

}  // namespace kiln::testing
