#include "render/reconstruction_filter.h"

#include <cmath>

#include "core/math.h"

namespace kiln {

float default_filter_radius(filter_kind kind) {
  switch (kind) {
    case filter_kind::box:
      return 0.5f;
    case filter_kind::tent:
      return 1.0f;
    case filter_kind::gaussian:
      return 1.5f;
    case filter_kind::blackman_harris:
      return 2.0f;
  }
  return 0.5f;
}

std::optional<filter_kind> parse_filter_kind(const std::string& name) {
  for (filter_kind k :
       {filter_kind::box, filter_kind::tent, filter_kind::gaussian, filter_kind::blackman_harris})
    if (name == filter_name(k)) return k;
  return std::nullopt;
}

const char* filter_name(filter_kind kind) {
  switch (kind) {
    case filter_kind::box:
      return "box";
    case filter_kind::tent:
      return "tent";
    case filter_kind::gaussian:
      return "gaussian";
    case filter_kind::blackman_harris:
      return "blackman-harris";
  }
  return "box";
}

float filter_weight_1d(const reconstruction_filter& f, float d) {
  const float r = f.radius;
  if (f.kind == filter_kind::box) return d >= -r && d < r ? 1.0f : 0.0f;
  const float a = std::abs(d);
  if (a >= r) return 0.0f;
  switch (f.kind) {
    case filter_kind::box:
      break;
    case filter_kind::tent:
      return 1.0f - a / r;
    case filter_kind::gaussian: {
      const float inv_two_sigma2 = 1.0f / (2.0f * (r / 3.0f) * (r / 3.0f));
      return std::max(0.0f, std::exp(-a * a * inv_two_sigma2) - std::exp(-r * r * inv_two_sigma2));
    }
    case filter_kind::blackman_harris: {
      // Harris 1978, the 4-term window with -92 dB side lobes; t runs 0..1 across the support.
      const float t = 0.5f + 0.5f * d / r;
      // cos 2x and cos 3x from cos x (Chebyshev): one cosine per weight instead of three.
      const float c = std::cos(2.0f * pi * t);
      const float c2 = 2.0f * c * c - 1.0f, c3 = (4.0f * c * c - 3.0f) * c;
      return 0.35875f - 0.48829f * c + 0.14128f * c2 - 0.01168f * c3;
    }
  }
  return 0.0f;
}

int filter_reach(const reconstruction_filter& f) { return std::max(0, int(std::ceil(f.radius - 0.5f))); }

}  // namespace kiln
