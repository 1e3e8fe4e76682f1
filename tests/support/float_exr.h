// Reads an EXR's every channel as float for tests (exact for half and float channels), with the
// spec for channel names, windows and header attributes.
#pragma once

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace kiln::testing {

struct float_exr {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;  // every channel converted to float, which is exact for half and float
};

// Fails the calling test (and returns an empty image) when the file cannot be read.
inline float_exr read_float_exr(const std::string& path) {
  float_exr out;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  if (!in) return out;
  out.spec = in->spec();
  out.pixels.resize(out.spec.image_pixels() * size_t(out.spec.nchannels));
  EXPECT_TRUE(in->read_image(0, 0, 0, out.spec.nchannels, OIIO::TypeDesc::FLOAT, out.pixels.data()));
  return out;
}

}  // namespace kiln::testing
