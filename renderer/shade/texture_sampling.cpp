#include "shade/texture_sampling.h"

#include <algorithm>
#include <cmath>

#include "shade/texture_filter.h"

namespace kiln {

namespace {

// How sample_texture reads a lookup.
enum class lookup_route { white, magnified, unfiltered, minified };

lookup_route route_of(const scene& s, const texture_filter* filter, const texture_lookup& l) {
  const texture& tex = s.textures[l.texture];
  const image& img = s.images[tex.image];
  if (!sampleable(img, l.uv)) return lookup_route::white;
  // OpenGL's rule: the scale factor ρ is the footprint's longest axis in texels; ρ ≤ 1 magnifies.
  const vec2 texels(img.width, img.height);
  const float rho = std::max(glm::length(l.footprint.dx * texels), glm::length(l.footprint.dy * texels));
  if (!(rho > 1.0f) || !std::isfinite(rho)) return lookup_route::magnified;
  if (tex.sampling.mipmap == mip_mode::none || !filter) return lookup_route::unfiltered;
  return lookup_route::minified;
}

void plan(const scene& s, const texture_filter* filter, const texture_lookup& l, lookup_route route,
          lookup_taps& taps) {
  const texture& tex = s.textures[l.texture];
  const image& img = s.images[tex.image];
  if (route == lookup_route::minified)
    return filter->minified_taps(l.texture, l.encoding, l.uv, l.footprint, taps);
  const filter_mode f = route == lookup_route::magnified ? tex.sampling.filter : tex.sampling.min_filter;
  level0_taps(img.width, img.height, l.uv, tex.sampling, f, taps);
}

vec4 read(const scene& s, const texture_filter* filter, const texture_lookup& l, lookup_route route,
          const lookup_taps& taps) {
  if (route == lookup_route::minified) return read_lookup(filter->pyramid(l.texture, l.encoding), taps);
  mip_pyramid level0;  // a view: no coarser levels
  level0.level0 = &s.images[s.textures[l.texture].image];
  level0.encoding = l.encoding;
  return read_lookup(level0, taps);
}

bool same_sampler(const sampler& a, const sampler& b) {
  return a.wrap_s == b.wrap_s && a.wrap_t == b.wrap_t && a.filter == b.filter &&
         a.min_filter == b.min_filter && a.mipmap == b.mipmap;
}

// Whether b's lookup is planned exactly as a's: an image of the same size (and, when minified,
// pyramid levels), equal samplers, uv and footprint.
bool shares_plan(const scene& s, const texture_filter* filter, const texture_lookup& a,
                 const texture_lookup& b, lookup_route route) {
  if (a.uv != b.uv || a.footprint.dx != b.footprint.dx || a.footprint.dy != b.footprint.dy) return false;
  const texture& ta = s.textures[a.texture];
  const texture& tb = s.textures[b.texture];
  const image& ia = s.images[ta.image];
  const image& ib = s.images[tb.image];
  if (ia.width != ib.width || ia.height != ib.height || !same_sampler(ta.sampling, tb.sampling)) return false;
  return route != lookup_route::minified ||
         filter->pyramid(a.texture, a.encoding).levels() == filter->pyramid(b.texture, b.encoding).levels();
}

}  // namespace

vec4 sample_texture(const scene& s, const texture_filter* filter, uint32_t texture_index, vec2 uv,
                    const uv_footprint& footprint, texel_encoding encoding) {
  const texture_lookup l{texture_index, encoding, uv, footprint};
  vec4 out;
  sample_textures(s, filter, &l, 1, &out);
  return out;
}

void sample_textures(const scene& s, const texture_filter* filter, const texture_lookup* lookups, int count,
                     vec4* out) {
  constexpr int batch = 8;
  if (count > batch) {
    sample_textures(s, filter, lookups, batch, out);
    return sample_textures(s, filter, lookups + batch, count - batch, out + batch);
  }
  bool done[batch] = {};
  lookup_taps taps;
  for (int i = 0; i < count; ++i) {
    if (done[i]) continue;
    const lookup_route route = route_of(s, filter, lookups[i]);
    if (route == lookup_route::white) {
      out[i] = vec4(1.0f);
      continue;
    }
    plan(s, filter, lookups[i], route, taps);
    out[i] = read(s, filter, lookups[i], route, taps);
    for (int j = i + 1; j < count; ++j)
      if (!done[j] && shares_plan(s, filter, lookups[i], lookups[j], route)) {
        out[j] = read(s, filter, lookups[j], route, taps);
        done[j] = true;
      }
  }
}

}  // namespace kiln
