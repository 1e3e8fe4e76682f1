// Filtered texture lookups for shading: a ray cone's footprint picks level 0 (magnification, or a
// sampler without mip-mapping) or the in-memory pyramids' anisotropic filter (minification).
// Point lookups, wrap modes and sRGB decoding live in scene/texture_eval.h.
#pragma once

#include "scene/scene.h"
#include "scene/texture_eval.h"

namespace kiln {

// A pixel's footprint in texture space: the two axes of the ellipse a ray cone covers, as changes
// of (u, v) (OpenImageIO's dsdx, dtdx and dsdy, dtdy). Both zero: a point sample.
struct uv_footprint {
  vec2 dx{0.0f};
  vec2 dy{0.0f};

  bool empty() const { return dx == vec2(0.0f) && dy == vec2(0.0f); }
};

class texture_filter;

// Filtered RGBA for a footprint: magnification (the footprint covers at most one texel) and
// samplers without mip-mapping read level 0 exactly as the point sample in scene/texture_eval.h,
// with the magFilter or minFilter respectively; mip-mapped minification goes to `filter`.
// A null filter or an empty footprint reads level 0.
vec4 sample_texture(const scene& s, const texture_filter* filter, uint32_t texture_index, vec2 uv,
                    const uv_footprint& footprint, texel_encoding encoding);

// One lookup of a batch: sample_texture's arguments.
struct texture_lookup {
  uint32_t texture = 0;
  texel_encoding encoding = texel_encoding::linear;
  vec2 uv{0.0f};
  uv_footprint footprint;
};

// out[i] = sample_texture(s, filter, lookups[i]...) for each of `count` lookups, bit for bit.
// Lookups of images of one size through equal samplers at an equal uv and footprint find their
// texels and weights once and read each image through them.
void sample_textures(const scene& s, const texture_filter* filter, const texture_lookup* lookups, int count,
                     vec4* out);

}  // namespace kiln
