// A texture's mip pyramid, held in memory: level 0 is the scene image itself (read texel by texel,
// 8-bit sRGB through a table), each coarser level the box average of the level above, in linear
// float RGBA (sRGB decoded first, so levels average linear values). OpenGL's sizes: each level
// halves both sides, rounding down, never below 1, until 1x1. Depends on scene only.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"
#include "scene/texture_eval.h"

namespace kiln {

struct mip_level {
  int width = 0;
  int height = 0;
  std::vector<vec4> texels;  // row-major, row 0 at the top
};

struct mip_pyramid {
  const image* level0 = nullptr;
  texel_encoding encoding = texel_encoding::linear;
  std::vector<mip_level> coarser;  // levels 1, 2, ... down to 1x1

  int levels() const { return 1 + int(coarser.size()); }
  int width(int level) const { return level == 0 ? level0->width : coarser[size_t(level - 1)].width; }
  int height(int level) const { return level == 0 ? level0->height : coarser[size_t(level - 1)].height; }
  // Texel (x, y) of level, in range, as linear RGBA.
  vec4 texel(int level, int x, int y) const {
    if (level == 0) return fetch_texel(*level0, x, y, encoding);
    const mip_level& l = coarser[size_t(level - 1)];
    return l.texels[size_t(y) * size_t(l.width) + size_t(x)];
  }
};

// The pyramid of img read with encoding; img must outlive it. Rows of each level are averaged in
// parallel on the caller's TBB arena; every texel is computed on its own, so the result does not
// depend on the thread count. A pyramid of levels 0 only (no coarser levels) when build is false.
mip_pyramid build_mip_pyramid(const image& img, texel_encoding encoding, bool build = true);

// The bytes of a pyramid's coarser levels over a width × height image (level 0 is the image).
uint64_t mip_pyramid_bytes(int width, int height);

// The texels one read of a level takes: the nearest texel (x0, y0), or the four around a point
// blended bilinearly, tx and ty the weights of x1 and y1. Where they lie depends on the level's size,
// the point and the sampler only, so reads of several images of one size at one point share them.
// No default values: a lookup holds dozens of these and fills only those it uses (mip_level_taps
// sets every field).
struct level_taps {
  int level;
  bool nearest;
  int x0;
  int x1;
  int y0;
  int y1;
  float tx;
  float ty;
};

// The taps of a read at uv (glTF UVs) of level `level`, width × height texels, by the sampler's
// wrap modes and `filter`.
level_taps mip_level_taps(int width, int height, int level, vec2 uv, const sampler& smp, filter_mode filter);

// mip_level_taps for level `level` (width × height) and level + 1 (coarser_width × coarser_height)
// at one uv, the same bits; both axes of both levels at once (SSE2, where the target has it) for
// bilinear reads under repeat wrapping, the common case.
void mip_level_pair_taps(int width, int height, int coarser_width, int coarser_height, int level, vec2 uv,
                         const sampler& smp, filter_mode filter, level_taps& finer, level_taps& coarser);

// The texels of p that t names, blended: linear RGBA (8-bit level 0 decoded by p's encoding). The
// same bits on every target: the SSE2 path does per channel the operations the scalar one does.
vec4 read_level_taps(const mip_pyramid& p, const level_taps& t);

// out[i] = read_level_taps(p, taps[i]) for each of `count` taps: one call for a whole lookup, the
// storage format decided once.
void read_level_taps(const mip_pyramid& p, const level_taps* taps, int count, vec4* out);

// One level of p read at uv (glTF UVs) by the sampler's wrap modes: the nearest texel, or the
// bilinear blend of the four around uv.
vec4 sample_mip_level(const mip_pyramid& p, int level, vec2 uv, const sampler& smp, filter_mode filter);

}  // namespace kiln
