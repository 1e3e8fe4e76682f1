#include "shade/texture_sampling.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "shade/mip_pyramid.h"
#include "shade/texture_filter.h"

namespace kiln {

float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

int wrap_texel(int i, int size, wrap_mode mode) {
  switch (mode) {
    case wrap_mode::clamp_to_edge:
      return i < 0 ? 0 : (i >= size ? size - 1 : i);
    case wrap_mode::mirrored_repeat: {
      int period = 2 * size;
      int m = i % period;
      if (m < 0) m += period;
      return m < size ? m : period - 1 - m;
    }
    case wrap_mode::repeat:
    default: {
      int m = i % size;
      return m < 0 ? m + size : m;
    }
  }
}

const std::array<float, 256> srgb8_to_linear = [] {
  std::array<float, 256> t{};
  for (int i = 0; i < 256; ++i) t[size_t(i)] = srgb_to_linear(float(i) / 255.0f);
  return t;
}();

namespace {

// Level 0 with one texel filter: nearest or bilinear.
vec4 sample_level0(const image& img, const sampler& smp, filter_mode filter, vec2 uv, texel_encoding encoding) {
  mip_pyramid level0;  // a view: no coarser levels
  level0.level0 = &img;
  level0.encoding = encoding;
  return sample_mip_level(level0, 0, uv, smp, filter);
}

bool sampleable(const image& img, vec2 uv) {
  return img.width > 0 && img.height > 0 && std::isfinite(uv.x) && std::isfinite(uv.y);
}

}  // namespace

vec2 transform_uv_vector(const texture_ref& ref, vec2 d) {
  vec2 scaled = d * ref.uv_scale;
  if (ref.rotation == 0.0f) return scaled;
  // Counter-clockwise as seen on the image, whose v axis points down: u' = c·u + s·v,
  // v' = -s·u + c·v (checked against the TextureTransformTest sample's green marker).
  const float c = std::cos(ref.rotation), s = std::sin(ref.rotation);
  return vec2(c * scaled.x + s * scaled.y, c * scaled.y - s * scaled.x);
}

vec2 transform_uv(const texture_ref& ref, vec2 uv) { return transform_uv_vector(ref, uv) + ref.offset; }

vec4 sample_texture(const scene& s, const texture& tex, vec2 uv, texel_encoding encoding) {
  const image& img = s.images[tex.image];
  if (!sampleable(img, uv)) return vec4(1.0f);
  return sample_level0(img, tex.sampling, tex.sampling.filter, uv, encoding);
}

vec4 sample_texture(const scene& s, const texture_filter* filter, uint32_t texture_index, vec2 uv,
                    const uv_footprint& footprint, texel_encoding encoding) {
  const texture& tex = s.textures[texture_index];
  const image& img = s.images[tex.image];
  if (!sampleable(img, uv)) return vec4(1.0f);
  // OpenGL's rule: the scale factor ρ is the footprint's longest axis in texels; ρ ≤ 1 magnifies.
  const vec2 texels(img.width, img.height);
  const float rho = std::max(glm::length(footprint.dx * texels), glm::length(footprint.dy * texels));
  if (!(rho > 1.0f) || !std::isfinite(rho))
    return sample_level0(img, tex.sampling, tex.sampling.filter, uv, encoding);
  if (tex.sampling.mipmap == mip_mode::none || !filter)
    return sample_level0(img, tex.sampling, tex.sampling.min_filter, uv, encoding);
  return filter->minified(texture_index, encoding, uv, footprint);
}

}  // namespace kiln
