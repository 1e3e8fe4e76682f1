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

// Intersects the sheared ray with triangle (p0, p1, p2), both faces, accepting t in (tmin, tmax]
// exactly as Embree's depth test does (tnear < t <= tfar): a hit at t == tmin, such as a shadow
// ray whose origin rounds back onto its own surface, is no hit. Returns false on a miss.
inline bool intersect_watertight(const sheared_ray& r, const vec3& p0, const vec3& p1, const vec3& p2,
                                 float tmin, float tmax, triangle_hit& out) {
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
  if (!(t > tmin && t <= tmax)) return false;
  // A t within its own rounding error of 0 may be the surface the ray just left (a shadow ray
  // whose offset origin still rounds onto its plane): bound that error as pbrt-v4 does for this
  // test (Pharr et al., 4th ed., section 6.8.7) and require t to exceed it. No global epsilon.
  const float max_x = std::max({std::abs(ax), std::abs(bx), std::abs(cx)});
  const float max_y = std::max({std::abs(ay), std::abs(by), std::abs(cy)});
  const float max_z = std::max({std::abs(az), std::abs(bz), std::abs(cz)});
  const float delta_x = gamma_bound(5) * (max_x + max_z);
  const float delta_y = gamma_bound(5) * (max_y + max_z);
  const float delta_z = gamma_bound(3) * max_z;
  const float delta_e = 2.0f * (gamma_bound(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
  const float max_e = std::max({std::abs(e0), std::abs(e1), std::abs(e2)});
  const float delta_t =
      3.0f * (gamma_bound(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * std::abs(inv_det);
  if (t <= delta_t) return false;
  out.t = t;
  out.u = e1 * inv_det;
  out.v = e2 * inv_det;
  return true;
}

}  // namespace kiln
