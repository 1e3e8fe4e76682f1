// The functions of the image codecs module, one file each; codecs_entry.cpp puts them in the
// table kiln loads. Internal to the module: the only kiln code that includes OpenImageIO.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace kiln::codecs_module {

// image_codecs::decode (memory_decode.cpp).
image decode(const uint8_t* data, size_t size, const std::string& name, const std::string& file,
             const std::string& where, uint64_t max_texels);

// image_codecs::read_float_rgba (file_read.cpp).
image read_float_rgba(const std::string& path, const std::string& where, uint64_t max_texels);

}  // namespace kiln::codecs_module
