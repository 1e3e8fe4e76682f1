#include "scene/texture_eval.h"

#include <cmath>

#include "scene/mip_pyramid.h"

namespace kiln {

std::array<texture_slot, 17> texture_slots(const material& m) {
  return {{{&m.base_color_texture, texel_encoding::srgb},
           {&m.emissive_texture, texel_encoding::srgb},
           {&m.metallic_roughness_texture, texel_encoding::linear},
           {&m.normal_texture, texel_encoding::linear},
           {&m.transmission_texture, texel_encoding::linear},
           {&m.specular_texture, texel_encoding::linear},
           {&m.specular_color_texture, texel_encoding::srgb},
           {&m.clearcoat_texture, texel_encoding::linear},
           {&m.clearcoat_roughness_texture, texel_encoding::linear},
           {&m.clearcoat_normal_texture, texel_encoding::linear},
           {&m.sheen_color_texture, texel_encoding::srgb},
           {&m.sheen_roughness_texture, texel_encoding::linear},
           {&m.iridescence_texture, texel_encoding::linear},
           {&m.iridescence_thickness_texture, texel_encoding::linear},
           {&m.diffuse_transmission_texture, texel_encoding::linear},
           {&m.diffuse_transmission_color_texture, texel_encoding::srgb},
           {&m.anisotropy_texture, texel_encoding::linear}}};
}

bool samples_textures(const material& m) {
  for (const texture_slot& slot : texture_slots(m))
    if (slot.ref->present()) return true;
  return false;
}

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

vec4 sample_level0(const image& img, const sampler& smp, filter_mode filter, vec2 uv,
                   texel_encoding encoding) {
  mip_pyramid level0;  // a view: no coarser levels
  level0.level0 = &img;
  level0.encoding = encoding;
  return sample_mip_level(level0, 0, uv, smp, filter);
}

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

}  // namespace kiln
