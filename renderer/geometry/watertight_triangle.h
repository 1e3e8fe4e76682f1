// The watertight ray-triangle test of Woop, Benthin and Wald, "Watertight Ray/Triangle
// Intersection" (JCGT 2013): shear the ray onto +Z, evaluate the three 2D edge functions, and
// redo them in double when one is exactly zero. Edges shared by two triangles give the same edge
// value with opposite sign, so no ray slips between them. Barycentrics follow Embree's convention
// p = (1-u-v)·p0 + u·p1 + v·p2. Depends on core only: accelerators and tests share it.
#pragma once

#include "core/math.h"

#include <algorithm>
#include <cmath>

namespace kiln {

// A ray prepared once for many triangle tests: the permuted axes and the shear constants.
struct sheared_ray {
  vec3 origin{0.0f};
  int kx = 0, ky = 1, kz = 2;
  float sx = 0.0f, sy = 0.0f, sz = 1.0f;
};

inline sheared_ray shear_ray(const vec3& origin, const vec3& direction) {
  sheared_ray s;
  s.origin = origin;
  vec3 a = glm::abs(direction);
  s.kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  s.kx = (s.kz + 1) % 3;
  s.ky = (s.kx + 1) % 3;
  // Swapping x and y for a negative z direction keeps the winding, hence the edge signs, intact.
  if (direction[s.kz] < 0.0f) std::swap(s.kx, s.ky);
  s.sx = direction[s.kx] / direction[s.kz];
  s.sy = direction[s.ky] / direction[s.kz];
  s.sz = 1.0f / direction[s.kz];
  return s;
}

// A triangle hit in ray parameter t with Embree-style barycentrics.
struct triangle_hit {
  float t = inf;
  float u = 0.0f;
  float v = 0.0f;
};

// Intersects the sheared ray with triangle (p0, p1, p2), both faces, accepting t in [tmin, tmax]
// inclusive as Embree does. Returns false on a miss.
inline bool intersect_watertight(const sheared_ray& r, const vec3& p0, const vec3& p1, const vec3& p2, float tmin,
                                 float tmax, triangle_hit& out) {
  const vec3 a = p0 - r.origin, b = p1 - r.origin, c = p2 - r.origin;
  const float ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
  const float bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
  const float cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];
  // Edge functions: e0 is opposite p0 (its weight), e1 opposite p1, e2 opposite p2.
  float e0 = cx * by - cy * bx;
  float e1 = ax * cy - ay * cx;
  float e2 = bx * ay - by * ax;
  if (e0 == 0.0f || e1 == 0.0f || e2 == 0.0f) {
    // On an edge within float precision: decide in double so neighbours agree (paper, section 3).
    e0 = float(double(cx) * double(by) - double(cy) * double(bx));
    e1 = float(double(ax) * double(cy) - double(ay) * double(cx));
    e2 = float(double(bx) * double(ay) - double(by) * double(ax));
  }
  if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) return false;
  const float det = e0 + e1 + e2;
  if (det == 0.0f) return false;
  const float az = r.sz * a[r.kz], bz = r.sz * b[r.kz], cz = r.sz * c[r.kz];
  const float scaled_t = e0 * az + e1 * bz + e2 * cz;
  // One division for t and both barycentrics; t is checked after it so tmin/tmax stay exact.
  const float inv_det = 1.0f / det;
  const float t = scaled_t * inv_det;
  if (!(t >= tmin && t <= tmax)) return false;
  out.t = t;
  out.u = e1 * inv_det;
  out.v = e2 * inv_det;
  return true;
}

}  // namespace kiln
