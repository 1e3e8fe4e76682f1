// Decodes the encoded glTF images (PNG, JPEG, ...) a scene uses into kiln images, in parallel,
// through the image codecs module (loaded here on the first image, never for a scene without
// any): 8-bit RGBA for 8-bit sources, float RGBA for deeper ones, row 0 at the top. Internal to
// io/gltf.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/memory_budget.h"
#include "scene/scene.h"

namespace kiln::gltf_internal {

// One image to decode: its encoded bytes (owned by the parsed model, which outlives the decode),
// the name the scene image gets and its JSON pointer (e.g. /images/3) for errors.
struct encoded_image {
  const uint8_t* data = nullptr;
  size_t size = 0;
  std::string name;
  std::string where;
};

// Decodes every image of `batch` (the format is recognised from its magic bytes, not from names or
// MIME types) on `threads` threads (0: all cores); the result is the same for any thread count.
// Alpha stays straight (unassociated), as glTF stores it. An image whose header declares more than
// max_texels texels is refused before it is decoded. Throws kiln::error (input) naming `file` and
// the first failing image in batch order, or (io) when the codecs module cannot be loaded. With a
// budget, the decoded images (kept) and the decoders' buffers (while they run) are charged to it
// from the headers before anything decodes.
std::vector<image> decode_images(const std::vector<encoded_image>& batch, const std::string& file,
                                 uint64_t max_texels, int threads = 0, memory_budget* memory = nullptr);

}  // namespace kiln::gltf_internal
