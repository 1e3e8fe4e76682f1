// The table of functions the image codecs module (kiln_image_codecs.so, the only kiln code that
// links OpenImageIO) hands to kiln. Both sides are built by the same toolchain from this header,
// so C++ types pass through it and the functions throw kiln::error. Depends on scene types only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace kiln {

// Bumped whenever the table below changes; kiln refuses a module built with another value.
constexpr uint32_t image_codecs_abi = 4;

struct image_codecs {
  uint32_t abi = image_codecs_abi;
  uint32_t table_bytes = sizeof(image_codecs);  // a second check that both sides agree on the layout

  // Decodes an encoded PNG, JPEG, WebP, GIF or BMP (recognised by its magic bytes) into 8-bit RGBA
  // for 8-bit sources, float RGBA otherwise, row 0 at the top, alpha straight. Refuses an image
  // whose header declares more than max_texels texels before decoding it. Throws kiln::error
  // (input) naming file and where (e.g. /images/3).
  image (*decode)(const uint8_t* data, size_t size, const std::string& name, const std::string& file,
                  const std::string& where, uint64_t max_texels) = nullptr;

  // Reads the image file at path (EXR, .hdr, anything OpenImageIO reads) as float RGBA: grey
  // becomes R = G = B, missing alpha 1. Throws kiln::error (input) naming path and where.
  image (*read_float_rgba)(const std::string& path, const std::string& where, uint64_t max_texels) = nullptr;
};

}  // namespace kiln

// The module's one exported symbol: its table, valid for the life of the process.
#define KILN_IMAGE_CODECS_ENTRY "kiln_image_codecs_table"
extern "C" const kiln::image_codecs* kiln_image_codecs_table();
