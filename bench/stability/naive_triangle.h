// The textbook Möller–Trumbore ray-triangle test in float, as the stability suite's naive
// variant: no watertight edge rule, no determinant guard, and reject-style comparisons (a NaN
// passes every "return false if out of range" check). kiln never renders with it; the tests show
// where it fails and kiln's methods do not. Depends on core only.
#pragma once

#include "core/math.h"

namespace kiln::bench {

struct naive_triangle_hit {
  float t = 0.0f, u = 0.0f, v = 0.0f;
};

inline bool intersect_naive_triangle(const vec3& o, const vec3& d, const vec3& p0, const vec3& p1,
                                     const vec3& p2, naive_triangle_hit& out) {
  const vec3 e1 = p1 - p0, e2 = p2 - p0;
  const vec3 pv = glm::cross(d, e2);
  const float inv_det = 1.0f / glm::dot(e1, pv);
  const vec3 tv = o - p0;
  const float u = glm::dot(tv, pv) * inv_det;
  if (u < 0.0f || u > 1.0f) return false;
  const vec3 qv = glm::cross(tv, e1);
  const float v = glm::dot(d, qv) * inv_det;
  if (v < 0.0f || u + v > 1.0f) return false;
  const float t = glm::dot(e2, qv) * inv_det;
  if (t < 0.0f) return false;
  out = {t, u, v};
  return true;
}

}  // namespace kiln::bench
