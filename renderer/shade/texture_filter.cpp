#include "shade/texture_filter.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace kiln {

namespace {

size_t slot(uint32_t image_index, texel_encoding encoding) {
  return size_t(image_index) * 2 + (encoding == texel_encoding::srgb ? 1 : 0);
}

// Per image and encoding (see slot()): whether some material reads it through a mip-mapped
// sampler. Base colour and emissive are sRGB; metallic-roughness, normal and transmission linear.
// Occlusion is not a shading input, so its image gets no pyramid.
std::vector<bool> mip_mapped_uses(const scene& s) {
  std::vector<bool> used(s.images.size() * 2, false);
  auto mark = [&](const texture_ref& ref, texel_encoding e) {
    if (!ref.present()) return;
    const texture& t = s.textures[size_t(ref.texture)];
    if (t.sampling.mipmap != mip_mode::none) used[slot(t.image, e)] = true;
  };
  for (const material& m : s.materials) {
    mark(m.base_color_texture, texel_encoding::srgb);
    mark(m.emissive_texture, texel_encoding::srgb);
    mark(m.metallic_roughness_texture, texel_encoding::linear);
    mark(m.normal_texture, texel_encoding::linear);
    mark(m.transmission_texture, texel_encoding::linear);
  }
  return used;
}

// The footprint's ellipse in level-0 texels: the singular values of [dx dy] (its semi-axes'
// lengths, major first) and the major axis' direction.
struct ellipse {
  float major = 0.0f;
  float minor = 0.0f;
  vec2 direction{1.0f, 0.0f};
};

ellipse footprint_ellipse(vec2 a, vec2 b) {
  // [dx dy]·[dx dy]ᵀ = [[A B] [B C]]; its eigenvalues are the squared singular values.
  const float A = a.x * a.x + b.x * b.x, B = a.x * a.y + b.x * b.y, C = a.y * a.y + b.y * b.y;
  const float mean = 0.5f * (A + C), spread = std::sqrt(0.25f * (A - C) * (A - C) + B * B);
  ellipse e;
  e.major = std::sqrt(mean + spread);
  e.minor = std::sqrt(std::max(mean - spread, 0.0f));
  // The major eigenvector: (B, λ - A) or (λ - C, B), whichever is longer (both are exact; the
  // longer one keeps its precision); a circle has no direction, so any will do.
  const float lambda = mean + spread;
  const vec2 u(B, lambda - A), v(lambda - C, B);
  const vec2 d = glm::dot(u, u) >= glm::dot(v, v) ? u : v;
  const float length = glm::length(d);
  if (length > 0.0f) e.direction = d / length;
  return e;
}

// One probe at uv with a filter `width` level-0 texels wide: the two levels whose texels are
// nearest that width, blended by width (the finer level alone when its texels are exactly as wide,
// the coarser alone when they are half as wide), or the nearest level alone.
vec4 probe(const mip_pyramid& p, vec2 uv, float width, const sampler& smp) {
  const int top = p.levels() - 1;
  const float lod = std::clamp(std::log2(std::max(width, 1.0f)), 0.0f, float(top));
  if (smp.mipmap == mip_mode::nearest)
    return sample_mip_level(p, int(std::lround(lod)), uv, smp, smp.min_filter);
  const int level = std::min(int(lod), top);
  const float coarser = std::exp2(lod - float(level)) - 1.0f;  // linear in width between the levels
  const vec4 finer = sample_mip_level(p, level, uv, smp, smp.min_filter);
  if (coarser <= 0.0f || level == top) return finer;
  return glm::mix(finer, sample_mip_level(p, level + 1, uv, smp, smp.min_filter), coarser);
}

}  // namespace

texture_filter::texture_filter(const scene& s) : scene_(s), pyramids_(s.images.size() * 2) {
  const std::vector<bool> used = mip_mapped_uses(s);
  for (size_t i = 0; i < s.images.size(); ++i)
    for (texel_encoding e : {texel_encoding::linear, texel_encoding::srgb})
      pyramids_[slot(uint32_t(i), e)] = build_mip_pyramid(s.images[i], e, false);
  // The pyramids are independent: build them in parallel (on the caller's arena, the render's
  // threads), each level's rows in parallel too.
  tbb::parallel_for(size_t(0), pyramids_.size(), [&](size_t k) {
    if (used[k]) pyramids_[k] = build_mip_pyramid(s.images[k / 2], pyramids_[k].encoding);
  });
}

vec4 texture_filter::minified(uint32_t texture_index, texel_encoding encoding, vec2 uv,
                              const uv_footprint& footprint) const {
  const texture& tex = scene_.textures[texture_index];
  const mip_pyramid& p = pyramids_[slot(tex.image, encoding)];
  if (p.width(0) <= 0 || p.height(0) <= 0) return vec4(1.0f);
  const vec2 texels(float(p.width(0)), float(p.height(0)));
  const ellipse e = footprint_ellipse(footprint.dx * texels, footprint.dy * texels);
  if (!(e.major > 0.0f) || !std::isfinite(e.major))
    return sample_mip_level(p, 0, uv, tex.sampling, tex.sampling.filter);
  // Probes as wide as the minor axis (widened so that the aspect is at most max_anisotropy),
  // 2·aspect - 1 of them spread evenly along the major axis over ±(major - minor), weighted by a
  // Gaussian of the distance from the centre: the elliptical filter OpenImageIO's TextureSystem
  // uses, which kiln used before it read its pyramids itself.
  const float minor = std::max(e.minor, e.major / float(max_anisotropy));
  const int n = std::clamp(int(2.0f * e.major / minor - 1.0f), 1, 2 * max_anisotropy - 1);
  if (n == 1) return probe(p, uv, minor, tex.sampling);
  const float reach = e.major - minor;
  const vec2 axis = e.direction * reach / texels;  // from the centre to the outermost probe, in UV
  vec4 sum(0.0f);
  float weights = 0.0f;
  for (int i = 0; i < n; ++i) {
    const float position = 2.0f * (float(i) + 0.5f) / float(n) - 1.0f;  // in (-1, 1)
    const float x = position * e.major / (2.0f * reach);
    const float w = n == 2 ? 1.0f : std::exp(-2.0f * x * x);
    sum += w * probe(p, uv + axis * position, minor, tex.sampling);
    weights += w;
  }
  return sum / weights;
}

bool scene_needs_texture_filter(const scene& s) {
  for (const texture& t : s.textures)
    if (t.sampling.mipmap != mip_mode::none) return true;
  return false;
}

}  // namespace kiln
