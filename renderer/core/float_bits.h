// Floating-point error bounds for robust secondary rays (pbrt-v4 util/float.h, Ray Tracing Gems
// ch. 6). No global epsilon: each spawned ray starts at an origin pushed off the surface by the
// bound of the hit point's rounding error. Depends on core/math only.
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>

#include "core/math.h"

namespace kiln {

constexpr float machine_epsilon = std::numeric_limits<float>::epsilon() * 0.5f;

// Bound on the relative error of n chained float operations, (n·ε)/(1 - n·ε).
constexpr float gamma_bound(int n) { return (n * machine_epsilon) / (1 - n * machine_epsilon); }

// The next representable float toward +infinity (or -infinity).
inline float next_float_up(float v) {
  if (std::isinf(v) && v > 0.0f) return v;
  if (v == -0.0f) v = 0.0f;
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  bits = v >= 0.0f ? bits + 1 : bits - 1;
  std::memcpy(&v, &bits, sizeof bits);
  return v;
}

inline float next_float_down(float v) {
  if (std::isinf(v) && v < 0.0f) return v;
  if (v == 0.0f) v = -0.0f;
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  bits = v > 0.0f ? bits - 1 : bits + 1;
  std::memcpy(&v, &bits, sizeof bits);
  return v;
}

// Moves a hit point p, known to within ±error per axis, off the surface with normal n to the side
// of direction w, far enough that a ray from it cannot re-hit the surface it left
// (pbrt-v4 OffsetRayOrigin). Each component is rounded away from p so the offset survives.
inline vec3 offset_ray_origin(const vec3& p, const vec3& error, const vec3& n, const vec3& w) {
  float d = glm::dot(glm::abs(n), error);
  vec3 offset = d * n;
  if (glm::dot(w, n) < 0.0f) offset = -offset;
  vec3 po = p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0.0f)
      po[i] = next_float_up(po[i]);
    else if (offset[i] < 0.0f)
      po[i] = next_float_down(po[i]);
  }
  return po;
}

}  // namespace kiln
