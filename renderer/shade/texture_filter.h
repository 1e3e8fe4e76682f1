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

// Everything a lookup decides before it reads a texel: the texels of each probe's level or two
// levels and the probes' weights. A pure function of the image's size and levels, the sampler, uv
// and the footprint, so lookups of several images of one size at one point (a material's base
// colour, metallic-roughness, normal and emissive maps, often) plan once and read each image.
struct lookup_taps {
  int probes = 1;           // 1: probe 0 alone; more: the weighted mean of probes 0 .. probes - 1
  bool two_levels = false;  // probe i blends taps[2i] and, by `coarser`, taps[2i + 1]; else taps[i]
  float coarser = 0.0f;
  float weights = 0.0f;  // the sum of weight[0 .. probes - 1], summed in that order
  // Left uninitialised: filled only as far as the probes go.
  float weight[2 * max_anisotropy - 1];
  level_taps taps[2 * (2 * max_anisotropy - 1)];
};

// Level 0 read at uv by `filter` alone (a magnified lookup, or a sampler without mip-mapping).
void level0_taps(int width, int height, vec2 uv, const sampler& smp, filter_mode filter, lookup_taps& out);

// The lookup t planned, read from p (a pyramid of an image of the size t was planned for).
vec4 read_lookup(const mip_pyramid& p, const lookup_taps& t);

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

  // minified()'s plan, read through read_lookup(pyramid(texture_index, encoding), out); the
  // texture's image must have texels.
  void minified_taps(uint32_t texture_index, texel_encoding encoding, vec2 uv, const uv_footprint& footprint,
                     lookup_taps& out) const;

  // Points the pyramids at s's images when they are the images they were built from, moved: s is
  // the scene the filter was made for, and every image a mip-mapped sampler reads holds the same
  // texel buffer (the same allocation, size and format) and is read the same ways. A loaded
  // scene's next pose moves its images into new places (job/loaded_scene.cpp), and its renders
  // then keep the pyramids instead of building them again. The caller must know that no image was
  // decoded or converted again in between (a freed buffer's address can come back): it drops the
  // filter whenever its pose did not carry the images over. Returns false, changing nothing,
  // otherwise.
  bool rebind(const scene& s);

  // The pyramid lookups of scene texture `texture_index` read (level 0 alone for textures no
  // mip-mapped sampler reads).
  const mip_pyramid& pyramid(uint32_t texture_index, texel_encoding encoding) const {
    return pyramids_[size_t(scene_.textures[texture_index].image) * 2 +
                     (encoding == texel_encoding::srgb ? 1 : 0)];
  }

 private:
  const scene& scene_;
  std::vector<mip_pyramid> pyramids_;  // per image and encoding: image * 2 + (srgb ? 1 : 0), as pyramid()
  std::vector<bool> used_;             // per slot as pyramids_: built beyond level 0
  std::vector<texel_buffer> sources_;  // per image: what it held when the pyramids were built
};

// The bytes the pyramids a texture_filter over s would build take (coarser levels only: level 0
// is the scene's image), for the job's memory budget before the filter is made.
uint64_t texture_filter_bytes(const scene& s);

// True when some material texture could be minified through a mip-mapped sampler (only then is a
// texture_filter worth building).
bool scene_needs_texture_filter(const scene& s);

}  // namespace kiln
