// Decodes the two image formats core glTF allows, 8-bit PNG and baseline or progressive JPEG, with
// libpng and libjpeg directly, in kiln itself: opening the image codecs module (OpenImageIO and its
// ~260 libraries) costs a textured render 0.17-0.25 s of process start on an idle machine, and
// seconds on a loaded one. The codes come out exactly as the module's: the same libraries with the
// same settings (libpng without gamma correction, palette and tRNS expanded; libjpeg's default
// DCT and upsampling), held together by tests/direct_decode_test.cpp on every sample image.
// Depends on scene types only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "scene/scene.h"

namespace kiln {

// The 8-bit RGBA image (alpha straight, row 0 at the top) that data encodes, or nothing when this
// decoder leaves it to the module: another format or bit depth (16-bit PNG, CMYK JPEG), more than
// max_texels texels, or data libpng or libjpeg finds anything wrong with (an error or a warning of
// libjpeg's: the module then refuses it with its own message, so errors read as they always did).
// Thread-safe; prints nothing.
std::optional<image> decode_directly(const uint8_t* data, size_t size, uint64_t max_texels);

}  // namespace kiln
