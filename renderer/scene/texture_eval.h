// Reading the Scene's textures and vertex attributes at a point: texel decoding (sRGB tables),
// glTF wrap modes, KHR_texture_transform, level-0 lookups by the sampler's filter, barycentric
// interpolation, and the list of a material's texture slots. Shading and the accelerators' alpha
// tests both read the scene through these; depends on scene only.
#pragma once

#include <array>
#include <cstdint>

#include "scene/scene.h"

namespace kiln {

// How a texture's texels are to be read.
enum class texel_encoding { linear, srgb };

// Interpolates attribute values with Embree's barycentric convention: (1-u-v)·a0 + u·a1 + v·a2.
template <typename T>
T interpolate(const T& a0, const T& a1, const T& a2, float u, float v) {
  return (1.0f - u - v) * a0 + u * a1 + v * a2;
}

// One texture input of a material and how its texels are encoded.
struct texture_slot {
  const texture_ref* ref = nullptr;
  texel_encoding encoding = texel_encoding::linear;
};

// Every texture a material's shading reads, with its encoding: the colour textures (base,
// emissive, specular, sheen and diffuse-transmission colour) are sRGB, every other input linear.
// A new texture input is added here once.
std::array<texture_slot, 17> texture_slots(const material& m);

// Whether shading reads any texture of m, so whether a hit needs its UV footprint at all.
bool samples_textures(const material& m);

// RGBA at uv (glTF convention: (0,0) is the top-left corner of the image) from level 0 by the
// sampler's magFilter (nearest or bilinear) and wrap modes. sRGB decoding applies to RGB, never to
// alpha, and happens before filtering. White for an empty image or a non-finite uv.
vec4 sample_texture(const scene& s, const texture& tex, vec2 uv, texel_encoding encoding);

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
      return {srgb8_to_linear[t[0]], srgb8_to_linear[t[1]], srgb8_to_linear[t[2]],
              float(t[3]) * (1.0f / 255.0f)};
    return vec4(float(t[0]), float(t[1]), float(t[2]), float(t[3])) * (1.0f / 255.0f);
  }
  const float* t = &img.texels32[i];
  if (encoding == texel_encoding::srgb)
    return {srgb_to_linear(t[0]), srgb_to_linear(t[1]), srgb_to_linear(t[2]), t[3]};
  return {t[0], t[1], t[2], t[3]};
}

// Maps an integer texel coordinate into [0, size) by a glTF wrap mode.
int wrap_texel(int i, int size, wrap_mode mode);

// Whether a lookup at uv can read img: it has texels and uv is finite.
inline bool sampleable(const image& img, vec2 uv) {
  return img.width > 0 && img.height > 0 && std::isfinite(uv.x) && std::isfinite(uv.y);
}

// Level 0 of img read at uv with one texel filter (nearest or bilinear) and smp's wrap modes.
vec4 sample_level0(const image& img, const sampler& smp, filter_mode filter, vec2 uv,
                   texel_encoding encoding);

}  // namespace kiln
