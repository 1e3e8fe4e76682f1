#include "scene/mip_pyramid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

// Row y of `level` of p as linear RGBA, each texel decoded once (level 0's 8-bit codes through the
// sRGB table or the 1/255 scale) rather than once per tap that reads it.
void decode_row(const mip_pyramid& p, int level, int y, vec4* row) {
  const int w = p.width(level);
  if (level > 0) {
    const mip_level& l = p.coarser[size_t(level - 1)];
    std::copy_n(l.texels.data() + size_t(y) * size_t(w), size_t(w), row);
    return;
  }
  for (int x = 0; x < w; ++x) row[x] = fetch_texel(*p.level0, x, y, p.encoding);
}

// Row y of `level` averaged along x into `row` (ow texels): exact pairs for an even width, the
// overlap weights for an odd one. `source` is scratch of the level's width.
void averaged_row(const mip_pyramid& p, int level, int y, const std::vector<box_taps>& tx, bool even_x,
                  std::vector<vec4>& source, vec4* row) {
  decode_row(p, level, y, source.data());
  const size_t ow = tx.size();
  if (even_x) {
    for (size_t x = 0; x < ow; ++x) row[x] = 0.5f * source[2 * x] + 0.5f * source[2 * x + 1];
    return;
  }
  for (size_t x = 0; x < ow; ++x) {
    const box_taps& t = tx[x];
    vec4 sum(0.0f);
    for (int k = 0; k < t.count; ++k) sum += t.weight[k] * source[size_t(t.first + k)];
    row[x] = sum;
  }
}

// The level below `finer` (level number `level` of p, already built), averaged along x then y.
// An even side averages exact pairs (0.5·a + 0.5·b, as the general taps compute it, so the result
// is the same bit for bit); an odd side goes through its overlap weights. Each target row averages
// the x-averaged source rows its taps name, computed for it alone: holding every x-averaged row
// at once would take twice the new level's memory (2 GiB under a 16384² texture).
mip_level next_level(const mip_pyramid& p, int level) {
  const int w = p.width(level), h = p.height(level);
  mip_level out;
  out.width = std::max(1, w / 2);
  out.height = std::max(1, h / 2);
  const std::vector<box_taps> tx = taps_for(w, out.width), ty = taps_for(h, out.height);
  const bool even_x = w == 2 * out.width, even_y = h == 2 * out.height;
  const size_t ow = size_t(out.width);
  out.texels.resize(ow * size_t(out.height));
  tbb::parallel_for(tbb::blocked_range<int>(0, out.height), [&](const tbb::blocked_range<int>& r) {
    std::vector<vec4> source(static_cast<size_t>(w));
    std::vector<vec4> rows(ow * 4);  // the x-averaged rows of one target row's taps (at most 4)
    for (int y = r.begin(); y < r.end(); ++y) {
      vec4* target = out.texels.data() + size_t(y) * ow;
      if (even_y) {
        averaged_row(p, level, 2 * y, tx, even_x, source, rows.data());
        averaged_row(p, level, 2 * y + 1, tx, even_x, source, rows.data() + ow);
        const vec4* a = rows.data();
        const vec4* b = a + ow;
        for (size_t x = 0; x < ow; ++x) target[x] = 0.5f * a[x] + 0.5f * b[x];
        continue;
      }
      const box_taps& t = ty[size_t(y)];
      for (int k = 0; k < t.count; ++k)
        averaged_row(p, level, t.first + k, tx, even_x, source, rows.data() + size_t(k) * ow);
      for (size_t x = 0; x < ow; ++x) {
        vec4 sum(0.0f);
        for (int k = 0; k < t.count; ++k) sum += t.weight[k] * rows[size_t(k) * ow + x];
        target[x] = sum;
      }
    }
  });
  return out;
}

// Wraps texel index i into [0, size), cheaply when it is in range already (nearly always).
int wrapped(int i, int size, wrap_mode mode) {
  return unsigned(i) < unsigned(size) ? i : wrap_texel(i, size, mode);
}

}  // namespace

uint64_t mip_pyramid_bytes(int width, int height) {
  uint64_t bytes = 0;
  while (width > 1 || height > 1) {
    width = std::max(1, width / 2);
    height = std::max(1, height / 2);
    bytes += uint64_t(width) * uint64_t(height) * sizeof(vec4);
  }
  return bytes;
}

mip_pyramid build_mip_pyramid(const image& img, texel_encoding encoding, bool build) {
  mip_pyramid p;
  p.level0 = &img;
  p.encoding = encoding;
  if (!build || img.width <= 0 || img.height <= 0) return p;
  for (int level = 0; p.width(level) > 1 || p.height(level) > 1; ++level)
    p.coarser.push_back(next_level(p, level));
  return p;
}

namespace {

// Four texels' weighted sum read by `read(x, y)`, one storage format per instantiation, so the
// format is decided once per lookup rather than per texel.
template <typename Read>
vec4 blend(const Read& read, int x0, int x1, int y0, int y1, float tx, float ty) {
  const vec4 top = glm::mix(read(x0, y0), read(x1, y0), tx);
  const vec4 bottom = glm::mix(read(x0, y1), read(x1, y1), tx);
  return glm::mix(top, bottom, ty);
}

// A texel's four channels as the blend holds them: one SSE2 register where the target has SSE2
// (every x86-64), else a vec4. Either way each channel goes through the same operations, rounded
// after each (SSE2 has no fused multiply-add), so both give the same bits.
#if defined(__SSE2__)
using lanes = __m128;

// glm::mix's a·(1 - t) + b·t, four channels at once.
[[gnu::always_inline]] inline lanes mix_lanes(lanes a, lanes b, float t) {
  return _mm_add_ps(_mm_mul_ps(a, _mm_set1_ps(1.0f - t)), _mm_mul_ps(b, _mm_set1_ps(t)));
}
[[gnu::always_inline]] inline lanes to_lanes(const vec4& v) { return _mm_loadu_ps(&v.x); }
[[gnu::always_inline]] inline lanes to_lanes(float r, float g, float b, float a) {
  return _mm_setr_ps(r, g, b, a);
}
// A float RGBA texel's four channels.
[[gnu::always_inline]] inline lanes float_lanes(const float* t) { return _mm_loadu_ps(t); }
// An 8-bit RGBA texel's four codes as floats (exact).
[[gnu::always_inline]] inline lanes code_lanes(const uint8_t* t) {
  int32_t word;
  std::memcpy(&word, t, sizeof word);
  const __m128i zero = _mm_setzero_si128();
  const __m128i bytes = _mm_cvtsi32_si128(word);
  return _mm_cvtepi32_ps(_mm_unpacklo_epi16(_mm_unpacklo_epi8(bytes, zero), zero));
}
[[gnu::always_inline]] inline vec4 to_vec4(lanes l) {
  vec4 out;
  _mm_storeu_ps(&out.x, l);
  return out;
}
#else
using lanes = vec4;

inline lanes mix_lanes(const lanes& a, const lanes& b, float t) { return glm::mix(a, b, t); }
inline lanes to_lanes(const vec4& v) { return v; }
inline lanes to_lanes(float r, float g, float b, float a) { return vec4(r, g, b, a); }
inline lanes float_lanes(const float* t) { return vec4(t[0], t[1], t[2], t[3]); }
inline lanes code_lanes(const uint8_t* t) { return vec4(float(t[0]), float(t[1]), float(t[2]), float(t[3])); }
inline vec4 to_vec4(const lanes& l) { return l; }
#endif

// blend() with the channels in lanes.
template <typename Read>
[[gnu::always_inline]] inline vec4 blend_lanes(const Read& read, int x0, int x1, int y0, int y1, float tx,
                                               float ty) {
  const lanes top = mix_lanes(read(x0, y0), read(x1, y0), tx);
  const lanes bottom = mix_lanes(read(x0, y1), read(x1, y1), tx);
  return to_vec4(mix_lanes(top, bottom, ty));
}

[[gnu::always_inline]] inline vec4 blend_level(const mip_pyramid& p, int level, int x0, int x1, int y0,
                                               int y1, float tx, float ty) {
  if (level > 0) {
    const mip_level& l = p.coarser[size_t(level - 1)];
    const vec4* texels = l.texels.data();
    const size_t w = size_t(l.width);
    return blend_lanes([&](int x, int y) { return to_lanes(texels[size_t(y) * w + size_t(x)]); }, x0, x1, y0,
                       y1, tx, ty);
  }
  const image& img = *p.level0;
  const size_t w = size_t(img.width);
  if (img.texels8.empty()) {
    // Linear float (an HDR environment map): the texels as they are, four channels at once.
    if (p.encoding == texel_encoding::linear) {
      const float* texels = img.texels32.data();
      return blend_lanes([&](int x, int y) { return float_lanes(texels + (size_t(y) * w + size_t(x)) * 4); },
                         x0, x1, y0, y1, tx, ty);
    }
    return blend([&](int x, int y) { return fetch_texel(img, x, y, p.encoding); }, x0, x1, y0, y1, tx, ty);
  }
  const uint8_t* texels = img.texels8.data();
  if (p.encoding == texel_encoding::srgb)
    return blend_lanes(
        [&](int x, int y) {
          const uint8_t* t = texels + (size_t(y) * w + size_t(x)) * 4;
          return to_lanes(srgb8_to_linear[t[0]], srgb8_to_linear[t[1]], srgb8_to_linear[t[2]],
                          float(t[3]) * (1.0f / 255.0f));
        },
        x0, x1, y0, y1, tx, ty);
  // Linear 8-bit: blend the codes, scale once.
  const vec4 codes =
      blend_lanes([&](int x, int y) { return code_lanes(texels + (size_t(y) * w + size_t(x)) * 4); }, x0, x1,
                  y0, y1, tx, ty);
  return codes * (1.0f / 255.0f);
}

}  // namespace

namespace {

// The two texels a bilinear read blends along one axis, and the weight of the second. The
// coordinate is first reduced to one period of the wrap mode (repeat: [0, 1), mirrored repeat:
// [0, 2)), so only a read across the image's edge needs wrapping; a division per texel (as
// wrap_texel does) cost more than the rest of the read.
struct texel_pair {
  int first = 0;
  int second = 0;
  float t = 0.0f;
};

// floor() as an int for |x| < 2^31, without a libm call: baseline x86-64 has no rounding
// instruction, and this runs several times per texture read.
int floor_to_int(float x) {
  const int i = int(x);
  return i - int(x < float(i));
}

// u reduced to one period of the wrap mode: [0, 1) for repeat, [0, 2) for mirrored repeat; clamped
// coordinates only need to stay in a range where converting to int is defined.
// Out of line and cold: the fmod() call kept pair_along() from being inlined into
// sample_mip_level(), and the call cost more than the arithmetic it does.
[[gnu::noinline, gnu::cold]] float huge_reduced(float u) { return std::fmod(u, 8388608.0f); }

[[gnu::always_inline]] inline float reduced(float u, wrap_mode mode) {
  if (mode == wrap_mode::clamp_to_edge) return std::clamp(u, -1.0f, 2.0f);
  if (!(std::abs(u) < 8388608.0f)) u = huge_reduced(u);  // floats this large are even integers
  if (mode == wrap_mode::repeat) return u - float(floor_to_int(u));
  return u - 2.0f * float(floor_to_int(0.5f * u));
}

[[gnu::always_inline]] inline texel_pair pair_along(float u, int size, wrap_mode mode) {
  const float x = reduced(u, mode) * float(size) - 0.5f;
  const int x0 = floor_to_int(x);
  texel_pair p;
  p.t = x - float(x0);
  p.first = wrapped(x0, size, mode);
  p.second = wrapped(x0 + 1, size, mode);
  return p;
}

int nearest_along(float u, int size, wrap_mode mode) {
  return wrapped(floor_to_int(reduced(u, mode) * float(size)), size, mode);
}

}  // namespace

level_taps mip_level_taps(int width, int height, int level, vec2 uv, const sampler& smp, filter_mode filter) {
  level_taps t;
  t.level = level;
  t.nearest = filter == filter_mode::nearest;
  if (t.nearest) {
    t.x0 = t.x1 = nearest_along(uv.x, width, smp.wrap_s);
    t.y0 = t.y1 = nearest_along(uv.y, height, smp.wrap_t);
    t.tx = t.ty = 0.0f;
    return t;
  }
  const texel_pair x = pair_along(uv.x, width, smp.wrap_s), y = pair_along(uv.y, height, smp.wrap_t);
  t.x0 = x.first;
  t.x1 = x.second;
  t.y0 = y.first;
  t.y1 = y.second;
  t.tx = x.t;
  t.ty = y.t;
  return t;
}

void mip_level_pair_taps(int width, int height, int coarser_width, int coarser_height, int level, vec2 uv,
                         const sampler& smp, filter_mode filter, level_taps& finer, level_taps& coarser) {
#if defined(__SSE2__)
  if (filter == filter_mode::linear && smp.wrap_s == wrap_mode::repeat && smp.wrap_t == wrap_mode::repeat) {
    // Lanes (u, v, u, v) over sizes (width, height, coarser_width, coarser_height): reduced(),
    // pair_along() and floor_to_int() lane by lane, the same operations in the same order.
    const __m128 u = _mm_setr_ps(uv.x, uv.y, uv.x, uv.y);
    const __m128 magnitude = _mm_andnot_ps(_mm_set1_ps(-0.0f), u);
    if (_mm_movemask_ps(_mm_cmplt_ps(magnitude, _mm_set1_ps(8388608.0f))) == 0xF) {
      auto floor4 = [](__m128 x) {
        const __m128i i = _mm_cvttps_epi32(x);
        return _mm_add_epi32(i, _mm_castps_si128(_mm_cmplt_ps(x, _mm_cvtepi32_ps(i))));  // - (x < i)
      };
      const __m128i sizes = _mm_setr_epi32(width, height, coarser_width, coarser_height);
      const __m128 reduced4 = _mm_sub_ps(u, _mm_cvtepi32_ps(floor4(u)));
      const __m128 x = _mm_sub_ps(_mm_mul_ps(reduced4, _mm_cvtepi32_ps(sizes)), _mm_set1_ps(0.5f));
      const __m128i first = floor4(x);
      const __m128i second = _mm_add_epi32(first, _mm_set1_epi32(1));
      alignas(16) int i0[4], i1[4], n[4];
      alignas(16) float t[4];
      _mm_store_si128(reinterpret_cast<__m128i*>(i0), first);
      _mm_store_si128(reinterpret_cast<__m128i*>(i1), second);
      _mm_store_si128(reinterpret_cast<__m128i*>(n), sizes);
      _mm_store_ps(t, _mm_sub_ps(x, _mm_cvtepi32_ps(first)));
      for (int k = 0; k < 4; ++k) {
        i0[k] = wrapped(i0[k], n[k], wrap_mode::repeat);
        i1[k] = wrapped(i1[k], n[k], wrap_mode::repeat);
      }
      finer = {level, false, i0[0], i1[0], i0[1], i1[1], t[0], t[1]};
      coarser = {level + 1, false, i0[2], i1[2], i0[3], i1[3], t[2], t[3]};
      return;
    }
  }
#endif
  finer = mip_level_taps(width, height, level, uv, smp, filter);
  coarser = mip_level_taps(coarser_width, coarser_height, level + 1, uv, smp, filter);
}

vec4 read_level_taps(const mip_pyramid& p, const level_taps& t) {
  if (t.nearest) return p.texel(t.level, t.x0, t.y0);
  return blend_level(p, t.level, t.x0, t.x1, t.y0, t.y1, t.tx, t.ty);
}

void read_level_taps(const mip_pyramid& p, const level_taps* taps, int count, vec4* out) {
  for (int i = 0; i < count; ++i) {
    const level_taps& t = taps[i];
    out[i] = t.nearest ? p.texel(t.level, t.x0, t.y0)
                       : blend_level(p, t.level, t.x0, t.x1, t.y0, t.y1, t.tx, t.ty);
  }
}

vec4 sample_mip_level(const mip_pyramid& p, int level, vec2 uv, const sampler& smp, filter_mode filter) {
  return read_level_taps(p, mip_level_taps(p.width(level), p.height(level), level, uv, smp, filter));
}

}  // namespace kiln
