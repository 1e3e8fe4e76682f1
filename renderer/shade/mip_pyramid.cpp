#include "shade/mip_pyramid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace kiln {

namespace {

// The source texels one target texel averages along one side shrinking from n to m texels: the
// box [x·n/m, (x+1)·n/m), each texel weighted by its overlap with the box (exactly 2×2 for even
// sides; an odd side spreads 2.5 or more texels over each target).
struct box_taps {
  int first = 0;
  int count = 0;
  float weight[4] = {0, 0, 0, 0};
};

std::vector<box_taps> taps_for(int n, int m) {
  std::vector<box_taps> taps(static_cast<size_t>(m));
  const double scale = double(n) / double(m);
  for (int x = 0; x < m; ++x) {
    const double lo = x * scale, hi = (x + 1) * scale;
    box_taps& t = taps[size_t(x)];
    t.first = int(std::floor(lo));
    const int last = std::min(n - 1, int(std::ceil(hi)) - 1);
    for (int i = t.first; i <= last && t.count < 4; ++i)
      t.weight[t.count++] = float((std::min(hi, double(i + 1)) - std::max(lo, double(i))) / scale);
  }
  return taps;
}

// The level below `finer` (level number `level` of p, already built), averaged along x then y.
mip_level next_level(const mip_pyramid& p, int level) {
  const int w = p.width(level), h = p.height(level);
  mip_level out;
  out.width = std::max(1, w / 2);
  out.height = std::max(1, h / 2);
  const std::vector<box_taps> tx = taps_for(w, out.width), ty = taps_for(h, out.height);
  std::vector<vec4> rows(size_t(out.width) * size_t(h));  // averaged along x only
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < out.width; ++x) {
      const box_taps& t = tx[size_t(x)];
      vec4 sum(0.0f);
      for (int k = 0; k < t.count; ++k) sum += t.weight[k] * p.texel(level, t.first + k, y);
      rows[size_t(y) * size_t(out.width) + size_t(x)] = sum;
    }
  });
  out.texels.resize(size_t(out.width) * size_t(out.height));
  tbb::parallel_for(0, out.height, [&](int y) {
    const box_taps& t = ty[size_t(y)];
    for (int x = 0; x < out.width; ++x) {
      vec4 sum(0.0f);
      for (int k = 0; k < t.count; ++k)
        sum += t.weight[k] * rows[size_t(t.first + k) * size_t(out.width) + size_t(x)];
      out.texels[size_t(y) * size_t(out.width) + size_t(x)] = sum;
    }
  });
  return out;
}

// Wraps texel index i into [0, size), cheaply when it is in range already (nearly always).
int wrapped(int i, int size, wrap_mode mode) {
  return unsigned(i) < unsigned(size) ? i : wrap_texel(i, size, mode);
}

// u, reduced modulo 65536 only when it is that large: fmod costs more than the rest of a read.
float bounded(float u) { return std::abs(u) < 65536.0f ? u : std::fmod(u, 65536.0f); }

}  // namespace

mip_pyramid build_mip_pyramid(const image& img, texel_encoding encoding, bool build) {
  mip_pyramid p;
  p.level0 = &img;
  p.encoding = encoding;
  if (!build || img.width <= 0 || img.height <= 0) return p;
  for (int level = 0; p.width(level) > 1 || p.height(level) > 1; ++level)
    p.coarser.push_back(next_level(p, level));
  return p;
}

vec4 sample_mip_level(const mip_pyramid& p, int level, vec2 uv, const sampler& smp, filter_mode filter) {
  const int w = p.width(level), h = p.height(level);
  // Texel centres sit at half-integers; keep the coordinate bounded before converting to int.
  const float fx = bounded(uv.x) * float(w) - 0.5f;
  const float fy = bounded(uv.y) * float(h) - 0.5f;
  if (filter == filter_mode::nearest)
    return p.texel(level, wrapped(int(std::floor(fx + 0.5f)), w, smp.wrap_s),
                   wrapped(int(std::floor(fy + 0.5f)), h, smp.wrap_t));
  const float x0f = std::floor(fx), y0f = std::floor(fy);
  const float tx = fx - x0f, ty = fy - y0f;
  const int x0 = wrapped(int(x0f), w, smp.wrap_s), x1 = wrapped(int(x0f) + 1, w, smp.wrap_s);
  const int y0 = wrapped(int(y0f), h, smp.wrap_t), y1 = wrapped(int(y0f) + 1, h, smp.wrap_t);
  const vec4 top = glm::mix(p.texel(level, x0, y0), p.texel(level, x1, y0), tx);
  const vec4 bottom = glm::mix(p.texel(level, x0, y1), p.texel(level, x1, y1), tx);
  return glm::mix(top, bottom, ty);
}

}  // namespace kiln
