// Reads a whole image file as float RGBA (the environment map's reader).
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <vector>

#include "core/error.h"
#include "io/image_codecs/module/codecs_module.h"

namespace kiln::codecs_module {

image read_float_rgba(const std::string& path, const std::string& where, uint64_t max_texels) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw input_error(path, where, "cannot read the image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const uint64_t texels = uint64_t(std::max(spec.width, 0)) * uint64_t(std::max(spec.height, 0));
  if (spec.width <= 0 || spec.height <= 0 || texels > max_texels || spec.nchannels <= 0)
    throw input_error(path, where, "unusable image size or channel count");
  const int channels = spec.nchannels;
  std::vector<float> pixels(texels * size_t(channels));
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw input_error(path, where, "cannot decode the image: " + in->geterror());
  image out;
  out.name = path;
  out.width = spec.width;
  out.height = spec.height;
  out.texels32.resize(texels * 4);
  for (size_t i = 0; i < texels; ++i) {
    const float* p = &pixels[i * size_t(channels)];
    float* q = &out.texels32[i * 4];
    for (int c = 0; c < 3; ++c) q[c] = channels >= 3 ? p[c] : p[0];  // grey maps to all three
    q[3] = channels >= 4 ? p[3] : 1.0f;
  }
  return out;
}

}  // namespace kiln::codecs_module
