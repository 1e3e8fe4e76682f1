// Mip-mapped texture filtering for minification through OpenImageIO's TextureSystem: each decoded
// scene image is served from memory (no files) to one ImageCache the process keeps for all its
// renders (each under names of its own, invalidated when its filter goes), as linear float (sRGB
// decoded before any mip level is built, so levels average linear values), with automip on.
// Lookups are pure functions of the image and the footprint, whatever the cache holds.
// Depends on scene (and OpenImageIO, hidden in the .cpp); never on a backend.
#pragma once

#include <memory>

#include "scene/scene.h"
#include "shade/texture_sampling.h"

namespace kiln {

class texture_filter {
 public:
  // Registers every texture of s (which must outlive the filter). cache_mb bounds OpenImageIO's
  // tile cache (it grows to at least twice the largest automipped image). The mip pyramids are
  // built in parallel on the calling thread's TBB arena; the result does not depend on its size.
  explicit texture_filter(const scene& s, float cache_mb = 256.0f);
  ~texture_filter();
  texture_filter(const texture_filter&) = delete;
  texture_filter& operator=(const texture_filter&) = delete;

  // Filtered RGBA of scene texture `texture_index` over the footprint around uv (glTF UVs, (0,0)
  // at the top-left): trilinear-anisotropic (mip_mode::linear) or one level (mip_mode::nearest),
  // texels read by the sampler's minFilter, wrapped by its wrap modes.
  vec4 minified(uint32_t texture_index, texel_encoding encoding, vec2 uv,
                const uv_footprint& footprint) const;

 private:
  struct impl;
  std::unique_ptr<impl> impl_;
};

// True when some material texture could be minified through a mip-mapped sampler (only then is a
// texture_filter worth building).
bool scene_needs_texture_filter(const scene& s);

}  // namespace kiln
