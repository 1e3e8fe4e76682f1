// Texture lookups for shading: glTF samplers (wrap modes, nearest or bilinear), sRGB decoding for
// colour textures. Depends on scene only; images were decoded by the loader.
#pragma once

#include <array>

#include "scene/scene.h"

namespace kiln {

// How a texture's texels are to be read.
enum class texel_encoding { linear, srgb };

// A pixel's footprint in texture space: the two axes of the ellipse a ray cone covers, as changes
// of (u, v) (OpenImageIO's dsdx, dtdx and dsdy, dtdy). Both zero: a point sample.
struct uv_footprint {
  vec2 dx{0.0f};
  vec2 dy{0.0f};

  bool empty() const { return dx == vec2(0.0f) && dy == vec2(0.0f); }
};

class texture_filter;

// Filtered RGBA at uv (glTF convention: (0,0) is the top-left corner of the image).
// sRGB decoding applies to RGB, never to alpha, and happens before filtering.
vec4 sample_texture(const scene& s, const texture& tex, vec2 uv, texel_encoding encoding);

// Filtered RGBA for a footprint: magnification (the footprint covers at most one texel) and
// samplers without mip-mapping read level 0 exactly as the point sample above, with the magFilter or
// minFilter respectively; mip-mapped minification goes to `filter` (OpenImageIO's TextureSystem).
// A null filter or an empty footprint reads level 0.
vec4 sample_texture(const scene& s, const texture_filter* filter, uint32_t texture_index, vec2 uv,
                    const uv_footprint& footprint, texel_encoding encoding);

// Applies a texture reference's KHR_texture_transform to uv (identity by default).
vec2 transform_uv(const texture_ref& ref, vec2 uv);

// KHR_texture_transform's linear part (scale, then rotation) applied to a UV difference.
vec2 transform_uv_vector(const texture_ref& ref, vec2 d);


// IEC 61966-2-1 sRGB transfer function, decoded to linear.
float srgb_to_linear(float c);

// srgb_to_linear(i / 255) for every 8-bit code i, computed once at start-up: a table lookup per
// channel keeps 8-bit textures in 8 bits of memory without paying pow() per texel.
extern const std::array<float, 256> srgb8_to_linear;

// Texel (x, y) of img (in range) as linear RGBA: sRGB decoding applies to RGB only. Inline: every
// filtered lookup reads four to dozens of texels.
inline vec4 fetch_texel(const image& img, int x, int y, texel_encoding encoding) {
  const size_t i = (size_t(y) * size_t(img.width) + size_t(x)) * 4;
  if (!img.texels8.empty()) {
    const uint8_t* t = &img.texels8[i];
    if (encoding == texel_encoding::srgb)
      return {srgb8_to_linear[t[0]], srgb8_to_linear[t[1]], srgb8_to_linear[t[2]], float(t[3]) * (1.0f / 255.0f)};
    return vec4(float(t[0]), float(t[1]), float(t[2]), float(t[3])) * (1.0f / 255.0f);
  }
  const float* t = &img.texels32[i];
  if (encoding == texel_encoding::srgb) return {srgb_to_linear(t[0]), srgb_to_linear(t[1]), srgb_to_linear(t[2]), t[3]};
  return {t[0], t[1], t[2], t[3]};
}

// Maps an integer texel coordinate into [0, size) by a glTF wrap mode.
int wrap_texel(int i, int size, wrap_mode mode);

}  // namespace kiln
