#include "shade/environment_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "shade/environment.h"

namespace kiln {

namespace {

// The linear RGB of texel (x, y) of a float or 8-bit linear image.
vec3 texel_rgb(const image& im, size_t x, size_t y) {
  const size_t i = (y * size_t(im.width) + x) * 4;
  if (!im.texels32.empty()) return vec3(im.texels32[i], im.texels32[i + 1], im.texels32[i + 2]);
  return vec3(im.texels8[i], im.texels8[i + 1], im.texels8[i + 2]) * (1.0f / 255.0f);
}

// Turns weights into a cumulative distribution from 0 to 1 (one entry more than weights), summed in
// double so a 16k-texel row keeps its small texels. Returns the sum; all-zero weights give a CDF
// that rises evenly, never drawn from (its row's marginal weight is 0).
double make_cdf(const float* weights, size_t n, float* cdf) {
  double sum = 0.0;
  cdf[0] = 0.0f;
  for (size_t i = 0; i < n; ++i) {
    sum += weights[i];
    cdf[i + 1] = float(sum);
  }
  for (size_t i = 1; i <= n; ++i) cdf[i] = sum > 0.0 ? float(double(cdf[i]) / sum) : float(i) / float(n);
  cdf[n] = 1.0f;
  return sum;
}

// The interval [cdf[k], cdf[k+1]) holding u, and u's place in it (in [0, 1)). Empty intervals are
// never chosen: the search lands past every entry equal to u. first, last: the intervals u can lie
// in (0 and n - 1 when nothing narrows it).
size_t find_interval(const float* cdf, size_t n, float u, float& within, size_t first = 0,
                     size_t last = ~size_t(0)) {
  last = std::min(last, n - 1);
  const size_t k = first + size_t(std::upper_bound(cdf + first + 1, cdf + last + 1, u) - (cdf + first + 1));
  const float width = cdf[k + 1] - cdf[k];
  within = width > 0.0f ? std::clamp((u - cdf[k]) / width, 0.0f, 0.99999994f) : 0.5f;
  return k;
}

// The guide table's size for a CDF of n intervals: the largest power of two at most n (at most
// 2^20), so that a bucket holds about one interval where the CDF rises evenly.
size_t guide_size(size_t n) {
  size_t g = 1;
  while (g * 2 <= n && g < (size_t(1) << 20)) g *= 2;
  return g;
}

// Fills guide (g + 1 entries) for the CDF of n intervals: entry b is the interval holding b / g,
// find_interval's (the count of cdf[1..n-1] at most b / g). The buckets' starts rise, so one walk
// along the CDF finds them all, in O(n + g): a search for each bucket took O(g log n), a third of
// a second for every render under a 4096x2048 map.
void make_guide(const float* cdf, size_t n, size_t g, uint32_t* guide) {
  size_t k = 0;
  for (size_t b = 0; b < g; ++b) {
    const float u = float(b) / float(g);
    while (k + 1 < n && cdf[k + 1] <= u) ++k;
    guide[b] = uint32_t(k);
  }
  guide[g] = uint32_t(n - 1);
}

// find_interval through the CDF's guide table: the same interval, searched for only between the
// intervals holding the bucket's two ends (u·g is exact, g a power of two).
// The guide table's bucket holding u (g buckets).
size_t guide_bucket(float u, size_t g) { return std::min(size_t(u * float(g)), g - 1); }

size_t find_guided(const float* cdf, size_t n, const uint32_t* guide, size_t g, float u, float& within) {
  const size_t b = guide_bucket(u, g);
  return find_interval(cdf, n, u, within, guide[b], guide[b + 1]);
}

// The map's weights: each texel's luminance times the solid angle it spans (sin θ at its row).
void build_map_distribution(const image& im, environment_light& e) {
  const size_t w = size_t(im.width), h = size_t(im.height);
  e.width = im.width;
  e.height = im.height;
  e.texel_density.resize(w * h);
  e.column_cdf.resize((w + 1) * h);
  e.row_cdf.resize(h + 1);
  std::vector<float> row_weight(h);
  e.column_guide_size = int(guide_size(w));
  const size_t gw = size_t(e.column_guide_size);
  e.column_guide.resize((gw + 1) * h);
  // Rows are independent: their weights, CDFs and guides are made in parallel (on the caller's
  // arena), each the same whatever thread makes it. A 4096x2048 map has 8 million texels.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, h, 16), [&](const tbb::blocked_range<size_t>& rows) {
    for (size_t y = rows.begin(); y < rows.end(); ++y) {
      const float sin_theta = std::sin(pi * (float(y) + 0.5f) / float(h));
      float* weights = &e.texel_density[y * w];
      for (size_t x = 0; x < w; ++x) weights[x] = std::max(luminance(texel_rgb(im, x, y)), 0.0f) * sin_theta;
      float* cdf = &e.column_cdf[y * (w + 1)];
      row_weight[y] = float(make_cdf(weights, w, cdf));
      make_guide(cdf, w, gw, &e.column_guide[y * (gw + 1)]);
    }
  });
  const double total = make_cdf(row_weight.data(), h, e.row_cdf.data());
  e.row_guide_size = int(guide_size(h));
  const size_t gh = size_t(e.row_guide_size);
  e.row_guide.resize(gh + 1);
  make_guide(e.row_cdf.data(), h, gh, e.row_guide.data());
  e.lights = total > 0.0;
  if (!e.lights) return;
  // Density over (u, v) in [0,1]²: weight / (total / texel count).
  const double scale = double(w) * double(h) / total;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, e.texel_density.size(), size_t(1) << 16),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t i = r.begin(); i < r.end(); ++i)
                        e.texel_density[i] = float(e.texel_density[i] * scale);
                    });
}

}  // namespace

uint64_t environment_light_bytes(const scene& s) {
  if (!s.env.has_map()) return 0;
  const image& im = s.images[size_t(s.env.map_image)];
  const uint64_t w = uint64_t(std::max(im.width, 0)), h = uint64_t(std::max(im.height, 0));
  const uint64_t guides = (guide_size(w) + 1) * h + guide_size(h) + 1;
  return (w + 1) * (h + 1) * 2 * sizeof(float) + guides * sizeof(uint32_t);
}

environment_light make_environment_light(const scene& s) {
  environment_light e;
  const environment& env = s.env;
  if (!env.has_map()) {
    e.lights = env.color.x > 0.0f || env.color.y > 0.0f || env.color.z > 0.0f;
    return e;
  }
  const image& im = s.images[size_t(env.map_image)];
  if (!(env.intensity > 0.0f) || im.width <= 0 || im.height <= 0) return e;
  e.uniform = false;
  e.rotation = env.rotation;
  e.source = texel_buffer_of(im);
  build_map_distribution(im, e);
  return e;
}

bool environment_light_fits(const environment_light& e, const scene& s) {
  const environment& env = s.env;
  if (e.uniform || !e.source.texels || !env.has_map() || !(env.intensity > 0.0f)) return false;
  return texel_buffer_of(s.images[size_t(env.map_image)]) == e.source;
}

vec3 environment_direction(const vec2& uv, float rotation_radians) {
  const float phi = (uv.x - 0.5f) * (2.0f * pi) + rotation_radians;
  const float theta = uv.y * pi;
  const float sin_theta = std::sin(theta);
  return {sin_theta * std::sin(phi), std::cos(theta), -sin_theta * std::cos(phi)};
}

namespace {

environment_sample sample_uniform_environment(const vec2& u) {
  environment_sample out;
  const float y = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::max(1.0f - y * y, 0.0f));
  const float phi = 2.0f * pi * u.y;
  out.direction = {r * std::cos(phi), y, r * std::sin(phi)};
  out.pdf = 1.0f / (4.0f * pi);
  return out;
}

// The sample of the map's texel (x, y), drawn at (du, dv) within it.
environment_sample map_sample(const environment_light& e, size_t x, size_t y, float du, float dv) {
  environment_sample out;
  const size_t w = size_t(e.width), h = size_t(e.height);
  const vec2 uv((float(x) + du) / float(w), (float(y) + dv) / float(h));
  out.uv = uv;
  out.direction = environment_direction(uv, e.rotation);
  const float sin_theta = std::sin(pi * uv.y);
  if (!(sin_theta > 0.0f)) return out;
  out.pdf = e.texel_density[y * w + x] / (2.0f * pi * pi * sin_theta);
  return out;
}

}  // namespace

environment_sample sample_environment(const environment_light& e, const vec2& u) {
  if (e.uniform) return sample_uniform_environment(u);
  const size_t w = size_t(e.width), h = size_t(e.height);
  float dv = 0.0f, du = 0.0f;
  const size_t gh = size_t(e.row_guide_size), gw = size_t(e.column_guide_size);
  const size_t y = find_guided(e.row_cdf.data(), h, e.row_guide.data(), gh, u.y, dv);
  const size_t x = find_guided(&e.column_cdf[y * (w + 1)], w, &e.column_guide[y * (gw + 1)], gw, u.x, du);
  return map_sample(e, x, y, du, dv);
}

void sample_environment_run(const environment_light& e, const vec2* u, int count, environment_sample* out) {
  if (e.uniform) {
    for (int i = 0; i < count; ++i) out[i] = sample_uniform_environment(u[i]);
    return;
  }
  // Each draw misses the cache three times in a row (its row's guide entry, then the CDF it points
  // into, then the texel's density); in stages over a few draws, each stage's loads are asked for
  // (prefetched) before any is waited on.
  constexpr int stage = 8;
  const size_t w = size_t(e.width), h = size_t(e.height);
  const size_t gh = size_t(e.row_guide_size), gw = size_t(e.column_guide_size);
  for (int first = 0; first < count; first += stage) {
    const int n = std::min(stage, count - first);
    size_t y[stage], x[stage];
    const uint32_t* guide[stage];
    float dv[stage], du[stage];
    for (int i = 0; i < n; ++i) {
      y[i] = find_guided(e.row_cdf.data(), h, e.row_guide.data(), gh, u[first + i].y, dv[i]);
      guide[i] = &e.column_guide[y[i] * (gw + 1) + guide_bucket(u[first + i].x, gw)];
      __builtin_prefetch(guide[i]);
    }
    for (int i = 0; i < n; ++i) __builtin_prefetch(&e.column_cdf[y[i] * (w + 1) + guide[i][0]]);
    for (int i = 0; i < n; ++i) {
      x[i] = find_interval(&e.column_cdf[y[i] * (w + 1)], w, u[first + i].x, du[i], guide[i][0], guide[i][1]);
      __builtin_prefetch(&e.texel_density[y[i] * w + x[i]]);
    }
    for (int i = 0; i < n; ++i) out[first + i] = map_sample(e, x[i], y[i], du[i], dv[i]);
  }
}

float environment_pdf(const environment_light& e, const vec3& d) {
  if (!e.lights) return 0.0f;
  if (e.uniform) return 1.0f / (4.0f * pi);
  return environment_pdf_at(e, d, environment_uv(d, e.rotation));
}

float environment_pdf_at(const environment_light& e, const vec3& d, const vec2& uv) {
  if (!e.lights) return 0.0f;
  if (e.uniform) return 1.0f / (4.0f * pi);
  const float sin_theta = std::sqrt(std::max(1.0f - d.y * d.y, 0.0f));
  if (!(sin_theta > 0.0f)) return 0.0f;
  const size_t x = std::min(size_t(uv.x * float(e.width)), size_t(e.width) - 1);
  const size_t y = std::min(size_t(uv.y * float(e.height)), size_t(e.height) - 1);
  return e.texel_density[y * size_t(e.width) + x] / (2.0f * pi * pi * sin_theta);
}

}  // namespace kiln
