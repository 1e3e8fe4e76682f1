#include "io/exr/environment_reader.h"

#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/openexr.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <vector>

#include "core/error.h"
#include "io/file/input_file.h"
#include "io/image_codecs/codecs_loader.h"

namespace kiln {

namespace {

// Largest environment kiln reads (a 16k x 8k map); a header claiming more is treated as corrupt.
constexpr uint64_t max_texels = uint64_t(1) << 27;

// Whether the file starts with OpenEXR's magic number.
bool is_exr(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) && std::memcmp(magic, "\x76\x2f\x31\x01", 4) == 0;
}

// The texels an OpenEXR file's header claims, read by OpenEXR's core library (the header alone:
// the C++ reader would first read a line offset table as long as the claimed height). 0 when the
// header cannot be read.
uint64_t claimed_exr_texels(const std::string& path) {
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = [](exr_const_context_t, exr_result_t, const char*) {};  // reported below
  exr_context_t context = nullptr;
  uint64_t texels = 0;
  exr_attr_box2i_t window{};
  if (exr_start_read(&context, path.c_str(), &init) == EXR_ERR_SUCCESS &&
      exr_get_data_window(context, 0, &window) == EXR_ERR_SUCCESS && window.max.x >= window.min.x &&
      window.max.y >= window.min.y)
    texels = uint64_t(int64_t(window.max.x) - window.min.x + 1) *
             uint64_t(int64_t(window.max.y) - window.min.y + 1);
  exr_finish(&context);
  return texels;
}

// An OpenEXR map read through OpenEXR itself (RGB, alpha ignored), so the studio environment of every
// default render, and any EXR map, costs no image codecs module.
image read_exr_environment(const std::string& path) {
  if (const uint64_t claimed = claimed_exr_texels(path); claimed > max_texels)
    throw input_error(path, "--environment",
                      "the image claims " + std::to_string(claimed) +
                          " texels, more than the largest environment map (2^27 texels)");
  try {
    Imf::RgbaInputFile file(path.c_str());
    const Imath::Box2i window = file.dataWindow();
    const uint64_t width = uint64_t(int64_t(window.max.x) - window.min.x + 1);
    const uint64_t height = uint64_t(int64_t(window.max.y) - window.min.y + 1);
    if (window.max.x < window.min.x || window.max.y < window.min.y || width * height > max_texels)
      throw input_error(path, "--environment",
                        "the image is " + std::to_string(width) + "x" + std::to_string(height) +
                            ", more than the largest environment map (2^27 texels)");
    std::vector<Imf::Rgba> pixels(width * height);
    file.setFrameBuffer(pixels.data() - window.min.x - int64_t(window.min.y) * int64_t(width), 1, width);
    file.readPixels(window.min.y, window.max.y);
    image out;
    out.name = path;
    out.width = int(width);
    out.height = int(height);
    out.texels32.resize(width * height * 4);
    for (uint64_t y = 0; y < height; ++y)
      for (uint64_t x = 0; x < width; ++x) {
        const Imf::Rgba& p = pixels[y * width + x];
        float* t = &out.texels32[(y * width + x) * 4];
        t[0] = p.r;
        t[1] = p.g;
        t[2] = p.b;
        t[3] = 1.0f;
      }
    return out;
  } catch (const error&) {
    throw;
  } catch (const std::exception& e) {
    throw input_error(path, "--environment", std::string("not a readable OpenEXR image: ") + e.what());
  }
}

}  // namespace

image read_environment_image(const std::string& path) {
  if (const std::string why = input_file_problem(path, max_environment_file_bytes); !why.empty())
    throw input_error(path, "--environment", why);
  image out =
      is_exr(path)
          ? read_exr_environment(path)
          : load_image_codecs("an environment map needs").read_float_rgba(path, "--environment", max_texels);
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
