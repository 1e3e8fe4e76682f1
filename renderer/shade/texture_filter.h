// Mip-mapped texture filtering for minification, over pyramids kiln builds and keeps in memory
// (scene/mip_pyramid.h): one per image and encoding that a mip-mapped sampler reads. A lookup is
// anisotropic: the footprint's ellipse is covered by n trilinear probes along its major axis, each
// at the level whose texels match the probe's width, n = the ellipse's aspect ratio rounded, at
// most max_anisotropy; a nearly round footprint is one isotropic trilinear probe. Lookups are pure
// functions of the image and the footprint. Depends on scene only; never on a backend.
#pragma once

#include <vector>

#include "scene/mip_pyramid.h"
#include "scene/scene.h"
#include "shade/texture_sampling.h"

namespace kiln {

// The most probes one lookup takes: footprints longer than this many times their width are
// blurred across (their width grows to major/16), as GPUs' 16x anisotropic filtering does.
constexpr int max_anisotropy = 16;

class texture_filter {
 public:
  // Builds the pyramids of every texture of s (which must outlive the filter) that a material
  // reads through a mip-mapped sampler, in parallel on the calling thread's TBB arena; the result
  // does not depend on its size.
  explicit texture_filter(const scene& s);
  texture_filter(const texture_filter&) = delete;
  texture_filter& operator=(const texture_filter&) = delete;

  // Filtered RGBA of scene texture `texture_index` over the footprint around uv (glTF UVs, (0,0)
  // at the top-left): anisotropic trilinear (mip_mode::linear) or the nearest level
  // (mip_mode::nearest), texels read by the sampler's minFilter, wrapped by its wrap modes.
  vec4 minified(uint32_t texture_index, texel_encoding encoding, vec2 uv,
                const uv_footprint& footprint) const;

 private:
  const scene& scene_;
  std::vector<mip_pyramid> pyramids_;  // per image and encoding: image * 2 + (srgb ? 1 : 0)
};

// The bytes the pyramids a texture_filter over s would build take (coarser levels only: level 0
// is the scene's image), for the job's memory budget before the filter is made.
uint64_t texture_filter_bytes(const scene& s);

// True when some material texture could be minified through a mip-mapped sampler (only then is a
// texture_filter worth building).
bool scene_needs_texture_filter(const scene& s);

}  // namespace kiln
