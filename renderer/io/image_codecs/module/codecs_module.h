// The functions of the image codecs module, one file each; codecs_entry.cpp puts them in the
// table kiln loads. Internal to the module: the only kiln code that includes OpenImageIO.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "io/colour/colour_module.h"
#include "scene/scene.h"

namespace kiln::codecs_module {

// image_codecs::decode (memory_decode.cpp).
image decode(const uint8_t* data, size_t size, const std::string& name, const std::string& file,
             const std::string& where, uint64_t max_texels);

// image_codecs::read_float_rgba (file_read.cpp).
image read_float_rgba(const std::string& path, const std::string& where, uint64_t max_texels);

// image_codecs::write_preview, preview_complete and write_preview_image (preview_codec.cpp).
void write_preview(const std::string& exr_path, const std::string& preview_path, double exposure,
                   const display_transform* view);
bool preview_complete(const std::string& preview_path, int width, int height);
void write_preview_image(const std::string& path, int width, int height, int channels,
                         const unsigned char* codes);

}  // namespace kiln::codecs_module
