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
// sampler.
std::vector<bool> mip_mapped_uses(const scene& s) {
  std::vector<bool> used(s.images.size() * 2, false);
  for (const material& m : s.materials)
    for (const texture_slot& slot : texture_slots(m)) {
      if (!slot.ref->present()) continue;
      const texture& t = s.textures[size_t(slot.ref->texture)];
      if (t.sampling.mipmap != mip_mode::none) used[kiln::slot(t.image, slot.encoding)] = true;
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

// The levels a filter `width` level-0 texels wide reads: the two whose texels are nearest that
// width, blended by width (the finer level alone when its texels are exactly as wide, the coarser
// alone when they are half as wide), or for mip_mode::nearest the nearest level alone. The same for
// every probe of a lookup, so computed once.
struct level_blend {
  int level = 0;
  float coarser = 0.0f;  // weight of level + 1
};

level_blend levels_for(const mip_pyramid& p, float width, const sampler& smp) {
  const int top = p.levels() - 1;
  const float lod = std::clamp(std::log2(std::max(width, 1.0f)), 0.0f, float(top));
  if (smp.mipmap == mip_mode::nearest) return {int(std::lround(lod)), 0.0f};
  level_blend b;
  b.level = std::min(int(lod), top);
  if (b.level < top) b.coarser = std::exp2(lod - float(b.level)) - 1.0f;  // linear in width
  return b;
}

// Probe i's taps at uv: level b.level and, when b blends, the next coarser one.
void probe_taps(const mip_pyramid& p, vec2 uv, const level_blend& b, const sampler& smp, int i,
                lookup_taps& out) {
  if (out.two_levels)
    return mip_level_pair_taps(p.width(b.level), p.height(b.level), p.width(b.level + 1),
                               p.height(b.level + 1), b.level, uv, smp, smp.min_filter, out.taps[2 * i],
                               out.taps[2 * i + 1]);
  out.taps[i] = mip_level_taps(p.width(b.level), p.height(b.level), b.level, uv, smp, smp.min_filter);
}

}  // namespace

void level0_taps(int width, int height, vec2 uv, const sampler& smp, filter_mode filter, lookup_taps& out) {
  out.probes = 1;
  out.two_levels = false;
  out.taps[0] = mip_level_taps(width, height, 0, uv, smp, filter);
}

vec4 read_lookup(const mip_pyramid& p, const lookup_taps& t) {
  const int stride = t.two_levels ? 2 : 1;
  vec4 texels[2 * (2 * max_anisotropy - 1)];
  read_level_taps(p, t.taps, t.probes * stride, texels);
  auto probe = [&](int i) {
    const vec4& finer = texels[stride * i];
    return t.two_levels ? glm::mix(finer, texels[stride * i + 1], t.coarser) : finer;
  };
  if (t.probes == 1) return probe(0);
  vec4 sum(0.0f);
  for (int i = 0; i < t.probes; ++i) sum += t.weight[i] * probe(i);
  return sum / t.weights;
}

texture_filter::texture_filter(const scene& s)
    : scene_(s), pyramids_(s.images.size() * 2), used_(mip_mapped_uses(s)) {
  for (size_t i = 0; i < s.images.size(); ++i) {
    sources_.push_back(texel_buffer_of(s.images[i]));
    for (texel_encoding e : {texel_encoding::linear, texel_encoding::srgb})
      pyramids_[slot(uint32_t(i), e)] = build_mip_pyramid(s.images[i], e, false);
  }
  // The pyramids are independent: build them in parallel (on the caller's arena, the render's
  // threads), each level's rows in parallel too.
  tbb::parallel_for(size_t(0), pyramids_.size(), [&](size_t k) {
    if (used_[k]) pyramids_[k] = build_mip_pyramid(s.images[k / 2], pyramids_[k].encoding);
  });
}

bool texture_filter::rebind(const scene& s) {
  if (&s != &scene_ || s.images.size() != sources_.size() || mip_mapped_uses(s) != used_) return false;
  for (size_t i = 0; i < sources_.size(); ++i)
    if ((used_[2 * i] || used_[2 * i + 1]) && !(texel_buffer_of(s.images[i]) == sources_[i])) return false;
  // Images no mip-mapped sampler reads have level 0 alone: any buffer serves them.
  for (size_t k = 0; k < pyramids_.size(); ++k) pyramids_[k].level0 = &s.images[k / 2];
  return true;
}

uint64_t texture_filter_bytes(const scene& s) {
  if (!scene_needs_texture_filter(s)) return 0;
  const std::vector<bool> used = mip_mapped_uses(s);
  uint64_t bytes = 0;
  for (size_t k = 0; k < used.size(); ++k)
    if (used[k]) bytes += mip_pyramid_bytes(s.images[k / 2].width, s.images[k / 2].height);
  return bytes;
}

namespace {

// What a lookup's footprint decides before any texel is read: the probes' count, spacing and
// levels. It depends on the footprint, the image's size and levels and the mip mode only.
struct lookup_plan {
  // The key.
  uv_footprint footprint;
  int width = 0;
  int height = 0;
  int levels = 0;
  mip_mode mipmap = mip_mode::none;
  // The plan.
  bool degenerate = false;  // no usable ellipse: level 0 through the magnification filter
  int n = 1;
  level_blend blend;
  vec2 axis{0.0f};  // from the centre to the outermost probe, in UV
  // Probe i lies at uv + axis · position[i] with weight weight[i]; weights is their sum in order.
  // They depend on the plan alone, so the slots that share it share the exp() calls too.
  float position[2 * max_anisotropy - 1];
  float weight[2 * max_anisotropy - 1];
  float weights = 0.0f;
};

lookup_plan plan_lookup(const mip_pyramid& p, const uv_footprint& footprint, const sampler& smp) {
  lookup_plan plan;
  plan.footprint = footprint;
  plan.width = p.width(0);
  plan.height = p.height(0);
  plan.levels = p.levels();
  plan.mipmap = smp.mipmap;
  const vec2 texels(float(plan.width), float(plan.height));
  const ellipse e = footprint_ellipse(footprint.dx * texels, footprint.dy * texels);
  if (!(e.major > 0.0f) || !std::isfinite(e.major)) {
    plan.degenerate = true;
    return plan;
  }
  // Probes as wide as the minor axis (widened so that the aspect is at most max_anisotropy),
  // 2·aspect - 1 of them spread evenly along the major axis over ±(major - minor), weighted by a
  // Gaussian of the distance from the centre: the elliptical filter OpenImageIO's TextureSystem
  // uses, which kiln used before it read its pyramids itself.
  const float minor = std::max(e.minor, e.major / float(max_anisotropy));
  plan.n = std::clamp(int(2.0f * e.major / minor - 1.0f), 1, 2 * max_anisotropy - 1);
  plan.blend = levels_for(p, minor, smp);
  const float reach = e.major - minor;
  plan.axis = e.direction * reach / texels;
  const int n = plan.n;
  float weights = 0.0f;
  for (int i = 0; i < n; ++i) {
    const float position = 2.0f * (float(i) + 0.5f) / float(n) - 1.0f;  // in (-1, 1)
    const float x = position * e.major / (2.0f * reach);
    // The centre probe of an odd n sits exactly at 0, where exp() would return exactly 1.
    const float w = n == 2 || x == 0.0f ? 1.0f : std::exp(-2.0f * x * x);
    plan.position[i] = position;
    plan.weight[i] = w;
    weights += w;
  }
  plan.weights = weights;
  return plan;
}

bool same_key(const lookup_plan& plan, const mip_pyramid& p, const uv_footprint& footprint,
              const sampler& smp) {
  return plan.width == p.width(0) && plan.height == p.height(0) && plan.levels == p.levels() &&
         plan.mipmap == smp.mipmap && plan.footprint.dx == footprint.dx && plan.footprint.dy == footprint.dy;
}

// The plan for this lookup, reused from this thread's previous lookup when its key matches: a
// material's texture slots (base colour, metallic-roughness, normal, emissive) are usually images
// of one size read over one footprint, so a hit plans once for all of them. A pure function of
// the key, so the cache changes no result.
const lookup_plan& plan_for(const mip_pyramid& p, const uv_footprint& footprint, const sampler& smp) {
  thread_local lookup_plan last;
  if (!same_key(last, p, footprint, smp)) last = plan_lookup(p, footprint, smp);
  return last;
}

}  // namespace

void texture_filter::minified_taps(uint32_t texture_index, texel_encoding encoding, vec2 uv,
                                   const uv_footprint& footprint, lookup_taps& out) const {
  const sampler& smp = scene_.textures[texture_index].sampling;
  const mip_pyramid& p = pyramid(texture_index, encoding);
  const lookup_plan& plan = plan_for(p, footprint, smp);
  if (plan.degenerate) return level0_taps(p.width(0), p.height(0), uv, smp, smp.filter, out);
  const int n = plan.n;
  out.probes = n;
  out.two_levels = plan.blend.coarser > 0.0f;
  out.coarser = plan.blend.coarser;
  if (n == 1) return probe_taps(p, uv, plan.blend, smp, 0, out);
  for (int i = 0; i < n; ++i) {
    out.weight[i] = plan.weight[i];
    probe_taps(p, uv + plan.axis * plan.position[i], plan.blend, smp, i, out);
  }
  out.weights = plan.weights;
}

vec4 texture_filter::minified(uint32_t texture_index, texel_encoding encoding, vec2 uv,
                              const uv_footprint& footprint) const {
  const mip_pyramid& p = pyramid(texture_index, encoding);
  if (p.width(0) <= 0 || p.height(0) <= 0) return vec4(1.0f);
  lookup_taps taps;
  minified_taps(texture_index, encoding, uv, footprint, taps);
  return read_lookup(p, taps);
}

bool scene_needs_texture_filter(const scene& s) {
  for (const texture& t : s.textures)
    if (t.sampling.mipmap != mip_mode::none) return true;
  return false;
}

}  // namespace kiln
