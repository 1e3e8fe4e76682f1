#include "io/exr/environment_reader.h"

#include <cmath>

#include "core/error.h"
#include "io/file/input_file.h"
#include "io/image_codecs/codecs_loader.h"

namespace kiln {

namespace {

// Largest environment kiln reads (a 16k x 8k map); a header claiming more is treated as corrupt.
constexpr uint64_t max_texels = uint64_t(1) << 27;

}  // namespace

image read_environment_image(const std::string& path) {
  if (const std::string why = input_file_problem(path, max_environment_file_bytes); !why.empty())
    throw input_error(path, "--environment", why);
  image out =
      load_image_codecs("an environment map needs").read_float_rgba(path, "--environment", max_texels);
  // Radiance is finite and not negative; anything else is a broken texel, read as black.
  for (size_t i = 0; i < out.texels32.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      const float v = out.texels32[i + c];
      out.texels32[i + c] = std::isfinite(v) && v > 0.0f ? v : 0.0f;
    }
    out.texels32[i + 3] = 1.0f;
  }
  return out;
}

}  // namespace kiln
