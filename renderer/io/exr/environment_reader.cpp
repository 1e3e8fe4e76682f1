#include "io/exr/environment_reader.h"

#include <OpenImageIO/imageio.h>

#include <cmath>

#include "core/error.h"
#include "io/file/input_file.h"

namespace kiln {

namespace {

// Largest environment kiln reads (a 16k x 8k map); a header claiming more is treated as corrupt.
constexpr uint64_t max_texels = uint64_t(1) << 27;

}  // namespace

image read_environment_image(const std::string& path) {
  if (const std::string why = input_file_problem(path, max_environment_file_bytes); !why.empty())
    throw input_error(path, "--environment", why);
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw input_error(path, "--environment", "cannot read the image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const uint64_t texels = uint64_t(std::max(spec.width, 0)) * uint64_t(std::max(spec.height, 0));
  if (spec.width <= 0 || spec.height <= 0 || texels > max_texels || spec.nchannels <= 0)
    throw input_error(path, "--environment", "unusable image size or channel count");
  const int channels = spec.nchannels;
  std::vector<float> pixels(texels * size_t(channels));
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw input_error(path, "--environment", "cannot decode the image: " + in->geterror());
  image out;
  out.name = path;
  out.width = spec.width;
  out.height = spec.height;
  out.texels32.resize(texels * 4);
  for (size_t i = 0; i < texels; ++i) {
    const float* p = &pixels[i * size_t(channels)];
    for (int c = 0; c < 3; ++c) {
      const float v = channels >= 3 ? p[c] : p[0];  // grey maps to all three
      // Radiance is finite and not negative; anything else is a broken texel, read as black.
      out.texels32[i * 4 + size_t(c)] = std::isfinite(v) && v > 0.0f ? v : 0.0f;
    }
    out.texels32[i * 4 + 3] = 1.0f;
  }
  return out;
}

}  // namespace kiln
