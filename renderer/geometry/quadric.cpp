// Bounds and ray intersection of the analytic primitives. Everything is double precision: the
// ray reaches object space through a double transform, and a ray from far away loses the hit in
// float (a sphere of radius 1 seen from 1e4 has c = |o|² − r² rounded to ~1e-3 in float, which
// moves the root by more than the sphere's size at grazing angles). Even in double the textbook
// discriminant b² − 4ac cancels catastrophically from 1e7 away, so every solve first moves the
// ray origin to the point of the ray closest to the primitive's centre (Ray Tracing Gems ch. 7):
// after that all coefficients are of the primitive's size and only a truly grazing ray cancels.
#include "geometry/quadric.h"

#include <algorithm>
#include <cmath>

#include "geometry/polynomial.h"
#include "geometry/quadric_implicit.h"

namespace kiln {

implicit_form implicit_of(const quadric& q) {
  implicit_form f;
  const double r2 = q.radius * q.radius;
  switch (q.kind) {
    case quadric_kind::sphere:
      f.a = dmat3(1.0);
      f.c = -r2;
      break;
    case quadric_kind::cylinder:
      f.a = dmat3(dvec3(1, 0, 0), dvec3(0, 1, 0), dvec3(0.0));
      f.c = -r2;
      break;
    case quadric_kind::cone: {  // x² + y² − k²(h − z)², k = r/h
      const double k2 = r2 / (q.height * q.height);
      f.a = dmat3(dvec3(1, 0, 0), dvec3(0, 1, 0), dvec3(0, 0, -k2));
      f.b = dvec3(0, 0, k2 * q.height);
      f.c = -k2 * q.height * q.height;
      break;
    }
    case quadric_kind::paraboloid:  // x² + y² − (r²/zmax)·z
      f.a = dmat3(dvec3(1, 0, 0), dvec3(0, 1, 0), dvec3(0.0));
      f.b = dvec3(0, 0, -0.5 * r2 / q.zmax);
      break;
    case quadric_kind::hyperboloid_one_sheet:     // x² + y² − (r/c)²z² − r²
    case quadric_kind::hyperboloid_two_sheets: {  // x² + y² − (r/c)²z² + r²
      const double k2 = r2 / (q.c * q.c);
      f.a = dmat3(dvec3(1, 0, 0), dvec3(0, 1, 0), dvec3(0, 0, -k2));
      f.c = q.kind == quadric_kind::hyperboloid_one_sheet ? -r2 : r2;
      break;
    }
    case quadric_kind::general: {
      const double* k = q.coefficients;
      f.a = dmat3(dvec3(k[0], 0.5 * k[3], 0.5 * k[4]), dvec3(0.5 * k[3], k[1], 0.5 * k[5]),
                  dvec3(0.5 * k[4], 0.5 * k[5], k[2]));
      f.b = dvec3(0.5 * k[6], 0.5 * k[7], 0.5 * k[8]);
      f.c = k[9];
      break;
    }
    case quadric_kind::disk:
    case quadric_kind::torus:
      break;  // not quadric side surfaces; handled separately
  }
  return f;
}

double quadric_radius_at(const quadric& q, double z) {
  switch (q.kind) {
    case quadric_kind::cylinder:
      return q.radius;
    case quadric_kind::cone:
      return q.radius * std::max(0.0, 1.0 - z / q.height);
    case quadric_kind::paraboloid:
      return q.radius * std::sqrt(std::max(0.0, z / q.zmax));
    case quadric_kind::hyperboloid_one_sheet:
      return q.radius * std::sqrt(1.0 + (z * z) / (q.c * q.c));
    case quadric_kind::hyperboloid_two_sheets:
      return q.radius * std::sqrt(std::max(0.0, (z * z) / (q.c * q.c) - 1.0));
    default:
      return q.radius;
  }
}

namespace {

bool is_axial(quadric_kind k) {
  return k == quadric_kind::cylinder || k == quadric_kind::cone || k == quadric_kind::paraboloid ||
         k == quadric_kind::hyperboloid_one_sheet || k == quadric_kind::hyperboloid_two_sheets;
}

// Is the side-surface point inside the primitive's clipping?
bool side_kept(const quadric& q, const dvec3& p) {
  if (q.kind == quadric_kind::general)
    return p.x >= q.box.lower.x && p.x <= q.box.upper.x && p.y >= q.box.lower.y && p.y <= q.box.upper.y &&
           p.z >= q.box.lower.z && p.z <= q.box.upper.z;
  if (is_axial(q.kind)) return p.z >= q.zmin && p.z <= q.zmax;
  return true;
}

// Keeps the closer of a candidate and the best hit so far.
void keep_closest(std::optional<quadric_ray_hit>& best, double t, uint32_t part) {
  if (!best || t < best->t) best = quadric_ray_hit{t, part};
}

// A disk z = z0, inner ≤ ρ ≤ outer, hit from the re-centred origin oc (t measured from oc).
void intersect_disk(const dvec3& oc, const dvec3& d, double t_offset, double z0, double inner, double outer,
                    double tmin, double tmax, uint32_t part, std::optional<quadric_ray_hit>& best) {
  if (d.z == 0.0 || outer <= 0.0) return;
  const double t_local = (z0 - oc.z) / d.z;
  const double t = t_offset + t_local;
  if (!(t > tmin && t < tmax)) return;
  const double x = oc.x + t_local * d.x, y = oc.y + t_local * d.y;
  const double rho2 = x * x + y * y;
  if (rho2 <= outer * outer && rho2 >= inner * inner) keep_closest(best, t, part);
}

// The clip box of a general quadric, shrunk to the quadric's own extent where that is bounded:
// an ellipsoid (A definite). With c' = b·A⁻¹b − c, F = (p − p0)ᵀA(p − p0) − c' about the centre
// p0 = −A⁻¹b, and the ellipsoid's half-width along axis i is √(c'·(A⁻¹)ᵢᵢ). For a box that cuts
// the ellipsoid the result is still conservative (the intersection of the two boxes), just not
// always tight; unbounded kinds (cylinders, cones, hyperboloids, paraboloids) keep the clip box.
bounds3 general_bounds(const quadric& q) {
  implicit_form f = implicit_of(q);
  const dmat3& a = f.a;
  const double minor2 = a[0][0] * a[1][1] - a[0][1] * a[1][0];
  const double det = glm::determinant(a);
  const double sign = a[0][0] > 0.0 && minor2 > 0.0 && det > 0.0   ? 1.0
                      : a[0][0] < 0.0 && minor2 > 0.0 && det < 0.0 ? -1.0
                                                                   : 0.0;
  if (sign == 0.0) return q.box;  // not definite: unbounded (or degenerate)
  const dmat3 inv = glm::inverse(sign * a);
  const dvec3 b = sign * f.b;
  const dvec3 center = -(inv * b);
  const double k = glm::dot(b, inv * b) - sign * f.c;
  if (!(k > 0.0) || !is_finite(center)) return q.box;  // empty or a single point
  bounds3 out;
  for (int i = 0; i < 3; ++i) {
    const double half = std::sqrt(k * inv[i][i]);
    out.lower[i] = std::max(q.box.lower[i], center[i] - half);
    out.upper[i] = std::min(q.box.upper[i], center[i] + half);
    if (!(out.lower[i] <= out.upper[i])) return q.box;  // the ellipsoid lies outside the box
  }
  return out;
}

}  // namespace

double quadric_implicit(const quadric& q, const dvec3& p) {
  if (q.kind == quadric_kind::torus) {
    const double big = q.major_radius * q.major_radius;
    const double s = glm::dot(p, p) + big - q.radius * q.radius;
    return s * s - 4.0 * big * (p.x * p.x + p.y * p.y);
  }
  if (q.kind == quadric_kind::disk) return p.z;
  return implicit_value(implicit_of(q), p);
}

dvec3 quadric_gradient(const quadric& q, const dvec3& p) {
  if (q.kind == quadric_kind::torus) {
    const double big = q.major_radius * q.major_radius;
    const double s = glm::dot(p, p) + big - q.radius * q.radius;
    return 4.0 * s * p - 8.0 * big * dvec3(p.x, p.y, 0.0);
  }
  if (q.kind == quadric_kind::disk) return dvec3(0, 0, 1);
  return implicit_gradient(implicit_of(q), p);
}

bounds3 quadric_bounds(const quadric& q) {
  bounds3 b;
  switch (q.kind) {
    case quadric_kind::sphere:
      b.lower = dvec3(-q.radius);
      b.upper = dvec3(q.radius);
      break;
    case quadric_kind::disk:
      b.lower = dvec3(-q.radius, -q.radius, 0.0);
      b.upper = dvec3(q.radius, q.radius, 0.0);
      break;
    case quadric_kind::torus: {
      const double outer = q.major_radius + q.radius;
      b.lower = dvec3(-outer, -outer, -q.radius);
      b.upper = dvec3(outer, outer, q.radius);
      break;
    }
    case quadric_kind::general:
      b = general_bounds(q);
      break;
    default: {
      // Axial kinds: the widest cross-section is at an end of [zmin, zmax] (the hyperboloid of
      // one sheet is narrowest at its waist, the others are monotonic in |z| or z).
      const double r = std::max(quadric_radius_at(q, q.zmin), quadric_radius_at(q, q.zmax));
      b.lower = dvec3(-r, -r, q.zmin);
      b.upper = dvec3(r, r, q.zmax);
    }
  }
  return b;
}

bool clip_ray_to_box(const bounds3& box, const dvec3& o, const dvec3& d, double& tmin, double& tmax) {
  for (int axis = 0; axis < 3; ++axis) {
    const double inv = 1.0 / d[axis];
    double t0 = (box.lower[axis] - o[axis]) * inv;
    double t1 = (box.upper[axis] - o[axis]) * inv;
    if (t0 > t1) std::swap(t0, t1);
    // A ray parallel to a slab gives ±inf or NaN (0·inf): NaN comparisons leave the range as is
    // when the origin is inside the slab, and an outside origin gives an empty range.
    if (d[axis] == 0.0) {
      if (o[axis] < box.lower[axis] || o[axis] > box.upper[axis]) return false;
      continue;
    }
    tmin = std::max(tmin, t0);
    tmax = std::min(tmax, t1);
    if (tmin > tmax) return false;
  }
  return true;
}

prepared_quadric prepare_quadric(const quadric& q) {
  prepared_quadric p;
  p.shape = &q;
  p.bounds = stored_quadric_bounds(q);
  // Grown by 1e-9 of the coordinates' magnitude per axis, so that rounding in the slab test cannot
  // reject a hit on a face of the bounds (a sphere's silhouette, a cap at zmin or zmax, a disk's
  // rim); the 1e-300 floor keeps the pad of an axis whose bounds are 0 from being zero.
  const dvec3 pad = 1e-9 * (glm::abs(p.bounds.lower) + glm::abs(p.bounds.upper)) + 1e-300;
  p.padded = bounds3{p.bounds.lower - pad, p.bounds.upper + pad};
  p.center = p.bounds.center();
  p.side = implicit_of(q);
  p.has_caps = q.caps && is_axial(q.kind);
  if (p.has_caps) {
    p.cap_radius_zmin = quadric_radius_at(q, q.zmin);
    p.cap_radius_zmax = quadric_radius_at(q, q.zmax);
  }
  return p;
}

std::optional<quadric_ray_hit> intersect_quadric(const quadric& q, const dvec3& o, const dvec3& d,
                                                 double tmin, double tmax) {
  return intersect_quadric(prepare_quadric(q), o, d, tmin, tmax);
}

std::optional<quadric_ray_hit> intersect_quadric(const prepared_quadric& p, const dvec3& o, const dvec3& d,
                                                 double tmin, double tmax, bool any_hit) {
  const quadric& q = *p.shape;
  // Every path returns `best`, so it is built in the caller's slot: returning another object
  // copied it there whole, a copy that stalled on the field-by-field stores just made.
  std::optional<quadric_ray_hit> best;
  // Slab-test the padded bounds first: it rejects most misses cheaply. Only the verdict is used:
  // the torus clips the ray to its own padded box for its root search (intersect_torus).
  double t_enter = tmin, t_exit = tmax;
  if (!clip_ray_to_box(p.padded, o, d, t_enter, t_exit)) return best;

  if (q.kind == quadric_kind::torus) {
    const std::optional<double> t = intersect_torus(q.major_radius, q.radius, o, d, tmin, tmax);
    if (t) best.emplace(quadric_ray_hit{*t, quadric_side});
    return best;
  }

  // Re-centre: o + t_c·d is the point of the ray closest to the centre of the bounds. Any ray
  // that can hit passes through the bounds, so after this every coefficient is O(size²).
  const dvec3& center = p.center;
  const double t_c = glm::dot(center - o, d) / glm::dot(d, d);
  const dvec3 oc = o + t_c * d;

  if (q.kind == quadric_kind::disk) {
    intersect_disk(oc, d, t_c, 0.0, q.inner_radius, q.radius, tmin, tmax, quadric_side, best);
    return best;
  }

  const implicit_form& f = p.side;
  const dvec3 a_d = f.a * d;
  const double a = glm::dot(d, a_d);
  const double h = glm::dot(a_d, oc) + glm::dot(f.b, d);
  const double c = glm::dot(oc, f.a * oc) + 2.0 * glm::dot(f.b, oc) + f.c;
  const polynomial_roots roots = solve_quadratic_half_b(a, h, c);
  for (int i = 0; i < roots.count; ++i) {
    const double t_local = roots.values[size_t(i)];
    const double t = t_c + t_local;
    if (!(t > tmin && t < tmax)) continue;
    if (!side_kept(q, oc + t_local * d)) continue;
    keep_closest(best, t, quadric_side);
    break;  // roots are ascending: the first kept one is the closest side hit
  }
  // Any hit answers an occlusion query: a cap could only be closer, not turn a hit into a miss.
  if (any_hit && best) return best;
  if (p.has_caps) {
    intersect_disk(oc, d, t_c, q.zmin, 0.0, p.cap_radius_zmin, tmin, tmax, quadric_cap_zmin, best);
    if (any_hit && best) return best;
    intersect_disk(oc, d, t_c, q.zmax, 0.0, p.cap_radius_zmax, tmin, tmax, quadric_cap_zmax, best);
  }
  return best;
}

}  // namespace kiln
