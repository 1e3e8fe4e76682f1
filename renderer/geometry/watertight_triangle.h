// The watertight ray-triangle test of Woop, Benthin and Wald, "Watertight Ray/Triangle
// Intersection" (JCGT 2013): shear the ray onto +Z, evaluate the three 2D edge functions, and
// redo them in double when one is exactly zero. Edges shared by two triangles give the same edge
// value with opposite sign, so no ray slips between them. Barycentrics follow Embree's convention
// p = (1-u-v)·p0 + u·p1 + v·p2. Depends on core only: accelerators and tests share it.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/float_bits.h"
#include "core/math.h"

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

// A triangle in the sheared ray's frame: vertex coordinates relative to the origin and the three
// edge functions (e0 is opposite p0, its weight; e1 opposite p1, e2 opposite p2).
struct sheared_triangle {
  float ax = 0, ay = 0, bx = 0, by = 0, cx = 0, cy = 0;  // sheared x, y
  float az = 0, bz = 0, cz = 0;                          // scaled z
  float e0 = 0, e1 = 0, e2 = 0;
};

inline sheared_triangle shear_triangle(const sheared_ray& r, const vec3& p0, const vec3& p1, const vec3& p2) {
  const vec3 a = p0 - r.origin, b = p1 - r.origin, c = p2 - r.origin;
  sheared_triangle s;
  s.ax = a[r.kx] - r.sx * a[r.kz], s.ay = a[r.ky] - r.sy * a[r.kz];
  s.bx = b[r.kx] - r.sx * b[r.kz], s.by = b[r.ky] - r.sy * b[r.kz];
  s.cx = c[r.kx] - r.sx * c[r.kz], s.cy = c[r.ky] - r.sy * c[r.kz];
  s.e0 = s.cx * s.by - s.cy * s.bx;
  s.e1 = s.ax * s.cy - s.ay * s.cx;
  s.e2 = s.bx * s.ay - s.by * s.ax;
  if (s.e0 == 0.0f || s.e1 == 0.0f || s.e2 == 0.0f) {
    // On an edge within float precision: decide in double so neighbours agree (paper, section 3).
    s.e0 = float(double(s.cx) * double(s.by) - double(s.cy) * double(s.bx));
    s.e1 = float(double(s.ax) * double(s.cy) - double(s.ay) * double(s.cx));
    s.e2 = float(double(s.bx) * double(s.ay) - double(s.by) * double(s.ax));
  }
  s.az = r.sz * a[r.kz], s.bz = r.sz * b[r.kz], s.cz = r.sz * c[r.kz];
  return s;
}

// The rounding-error bound of the test's t, as pbrt-v4 bounds it (Pharr et al., 4th ed., section
// 6.8.7). It grows with the triangle's extent squared over its area: a long sliver has a wide one.
inline float watertight_t_bound(const sheared_triangle& s, float inv_det) {
  const float max_x = std::max({std::abs(s.ax), std::abs(s.bx), std::abs(s.cx)});
  const float max_y = std::max({std::abs(s.ay), std::abs(s.by), std::abs(s.cy)});
  const float max_z = std::max({std::abs(s.az), std::abs(s.bz), std::abs(s.cz)});
  const float delta_x = gamma_bound(5) * (max_x + max_z);
  const float delta_y = gamma_bound(5) * (max_y + max_z);
  const float delta_z = gamma_bound(3) * max_z;
  const float delta_e = 2.0f * (gamma_bound(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
  const float max_e = std::max({std::abs(s.e0), std::abs(s.e1), std::abs(s.e2)});
  return 3.0f * (gamma_bound(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * std::abs(inv_det);
}

// Intersects the sheared ray with triangle (p0, p1, p2), both faces, accepting t in (tmin, tmax]
// exactly as Embree's depth test does (tnear < t <= tfar): a hit at t == tmin, such as a shadow
// ray whose origin rounds back onto its own surface, is no hit. Returns false on a miss.
inline bool intersect_watertight(const sheared_ray& r, const vec3& p0, const vec3& p1, const vec3& p2,
                                 float tmin, float tmax, triangle_hit& out) {
  const sheared_triangle s = shear_triangle(r, p0, p1, p2);
  if ((s.e0 < 0.0f || s.e1 < 0.0f || s.e2 < 0.0f) && (s.e0 > 0.0f || s.e1 > 0.0f || s.e2 > 0.0f))
    return false;
  const float det = s.e0 + s.e1 + s.e2;
  if (det == 0.0f) return false;
  const float scaled_t = s.e0 * s.az + s.e1 * s.bz + s.e2 * s.cz;
  // One division for t and both barycentrics; t is checked after it so tmin/tmax stay exact.
  const float inv_det = 1.0f / det;
  const float t = scaled_t * inv_det;
  if (!(t > tmin && t <= tmax)) return false;
  // A t within its own rounding error of 0 may be the surface the ray just left (a shadow ray
  // whose offset origin still rounds onto its plane): require t to exceed the error bound. No
  // global epsilon. Embree has no such rejection: accelerator comparisons account for it
  // (accel/compare/hit_comparison.h).
  if (t <= watertight_t_bound(s, inv_det)) return false;
  out.t = t;
  out.u = s.e1 * inv_det;
  out.v = s.e2 * inv_det;
  return true;
}

}  // namespace kiln
