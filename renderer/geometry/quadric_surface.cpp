// The surface at a quadric hit: projection onto the exact surface, gradient normal, parametric
// UV and tangent, and the error bound of the point; then the same in world space.
// Projecting the point (instead of trusting o + t·d) makes the hit point's error independent of
// how t was found and of how far the ray travelled, which is what lets secondary rays start
// at an offset of a few ulps (pbrt-v4 reprojects its sphere hits for the same reason).
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/float_bits.h"
#include "geometry/quadric.h"
#include "geometry/quadric_implicit.h"

namespace kiln {

namespace {

constexpr double double_epsilon = std::numeric_limits<double>::epsilon();
constexpr double two_pi = 6.283185307179586476925;

// Azimuth in [0, 1): u of every rotationally symmetric kind, measured from +x toward +y.
double azimuth_u(const dvec3& p) {
  double phi = std::atan2(p.y, p.x);
  if (phi < 0.0) phi += two_pi;
  return phi / two_pi;
}

// A unit tangent along increasing u: the azimuthal direction (−y, x, 0), or, where it vanishes
// (poles, apex, disk centre), any unit vector perpendicular to the normal.
dvec3 azimuthal_tangent(const dvec3& p, const dvec3& normal) {
  dvec3 t(-p.y, p.x, 0.0);
  t -= glm::dot(t, normal) * normal;
  const double len = glm::length(t);
  if (len > 1e-12 * (glm::length(p) + 1e-300)) return t / len;
  vec3 a, b;
  orthonormal_basis(vec3(normal), a, b);
  return dvec3(a);
}

double clamp01(double x) { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }

// The u, v of a point on the side surface (docs/quadrics.md).
dvec2 side_uv(const quadric& q, const dvec3& p) {
  switch (q.kind) {
    case quadric_kind::sphere:
      return dvec2(azimuth_u(p), std::acos(std::clamp(p.z / q.radius, -1.0, 1.0)) / (two_pi / 2.0));
    case quadric_kind::torus: {
      // Tube angle measured downward on the outside, so +z is the image's up there too.
      double theta = std::atan2(-p.z, std::sqrt(p.x * p.x + p.y * p.y) - q.major_radius);
      if (theta < 0.0) theta += two_pi;
      return dvec2(azimuth_u(p), theta / two_pi);
    }
    case quadric_kind::disk:
      return dvec2(azimuth_u(p), clamp01((std::sqrt(p.x * p.x + p.y * p.y) - q.inner_radius) /
                                         (q.radius - q.inner_radius)));
    case quadric_kind::general: {
      const dvec3 extent = q.box.diagonal();
      return dvec2(extent.x > 0.0 ? clamp01((p.x - q.box.lower.x) / extent.x) : 0.0,
                   extent.y > 0.0 ? clamp01((q.box.upper.y - p.y) / extent.y) : 0.0);
    }
    default:  // axial kinds: around the axis, then down it from zmax (the image's top)
      return dvec2(azimuth_u(p), clamp01((q.zmax - p.z) / (q.zmax - q.zmin)));
  }
}

// F and ∇F of the side surface with the kind's matrix form built once: the projection below
// evaluates both up to seven times per hit. Same values as quadric_implicit / quadric_gradient.
struct side_function {
  const quadric& q;
  implicit_form f;
  explicit side_function(const quadric& quadric_) : q(quadric_) {
    if (q.kind != quadric_kind::torus && q.kind != quadric_kind::disk) f = implicit_of(q);
  }
  double value(const dvec3& p) const {
    if (q.kind == quadric_kind::torus || q.kind == quadric_kind::disk) return quadric_implicit(q, p);
    return implicit_value(f, p);
  }
  dvec3 gradient(const dvec3& p) const {
    if (q.kind == quadric_kind::torus || q.kind == quadric_kind::disk) return quadric_gradient(q, p);
    return implicit_gradient(f, p);
  }
};

// Newton steps along the gradient onto F = 0: each step removes the first-order residual.
dvec3 project_to_side(const side_function& side, dvec3 p) {
  const quadric& q = side.q;
  if (q.kind == quadric_kind::sphere) {
    const double len = glm::length(p);
    return len > 0.0 ? p * (q.radius / len) : p;
  }
  if (q.kind == quadric_kind::disk) return dvec3(p.x, p.y, 0.0);
  for (int step = 0; step < 3; ++step) {
    const double f = side.value(p);
    const dvec3 g = side.gradient(p);
    const double g2 = glm::dot(g, g);
    if (f == 0.0 || !(g2 > 0.0)) break;
    const dvec3 next = p - (f / g2) * g;
    if (!is_finite(next)) break;
    p = next;
  }
  return p;
}

bool is_cap(uint32_t part) { return part == quadric_cap_zmin || part == quadric_cap_zmax; }

// A cap hit: the point moved onto the cap's plane, and the cap's uv (see quadric_surface_at).
dvec3 cap_point(const quadric& q, uint32_t part, const dvec3& approx_point) {
  return dvec3(approx_point.x, approx_point.y, part == quadric_cap_zmin ? q.zmin : q.zmax);
}
dvec2 cap_uv(const quadric& q, const dvec3& point) {
  const double cap_radius = quadric_radius_at(q, point.z);
  const double rho = std::sqrt(point.x * point.x + point.y * point.y);
  return dvec2(azimuth_u(point), cap_radius > 0.0 ? clamp01(rho / cap_radius) : 0.0);
}

// The unit side normal from the gradient g at a projected point (the axis where g vanishes).
dvec3 side_normal(const dvec3& g, double g_len) {
  return g_len > 0.0 && std::isfinite(g_len) ? g / g_len : dvec3(0.0, 0.0, 1.0);
}

// The projected point and unit normal of `part` near approx_point: quadric_surface_at without
// uv, tangent and error, for the curvature's neighbouring points.
void point_and_normal_at(const side_function& side, uint32_t part, const dvec3& approx_point, dvec3& point,
                         dvec3& normal) {
  if (is_cap(part)) {
    point = cap_point(side.q, part, approx_point);
    normal = dvec3(0.0, 0.0, part == quadric_cap_zmin ? -1.0 : 1.0);
    return;
  }
  point = project_to_side(side, approx_point);
  const dvec3 g = side.gradient(point);
  normal = side_normal(g, glm::length(g));
}

// quadric_surface_at(q, part, approx_point).uv, without the normal, tangent and error.
dvec2 uv_at(const side_function& side, uint32_t part, const dvec3& approx_point) {
  if (is_cap(part)) return cap_uv(side.q, cap_point(side.q, part, approx_point));
  return side_uv(side.q, project_to_side(side, approx_point));
}

// The hit of world ray r at t, moved to object space in double: the intersector's transform.
dvec3 object_hit_point(const instance& inst, const ray& r, float t) {
  const dvec3 o = transform_point(inst.object_from_world, dvec3(r.origin));
  const dvec3 d = transform_vector(inst.object_from_world, dvec3(r.direction));
  return o + double(t) * d;
}

}  // namespace

quadric_surface quadric_surface_at(const quadric& q, uint32_t part, const dvec3& approx_point) {
  quadric_surface s;
  const double size = glm::length(stored_quadric_bounds(q).diagonal());
  if (is_cap(part)) {
    s.point = cap_point(q, part, approx_point);
    s.normal = dvec3(0.0, 0.0, part == quadric_cap_zmin ? -1.0 : 1.0);
    s.uv = cap_uv(q, s.point);
    s.dpdu = azimuthal_tangent(s.point, s.normal);
    // Seen from outside, the zmin cap's u runs clockwise (it continues the side's u across the
    // rim), so its frame is mirrored: v grows outward and normal × dpdu points outward too.
    s.handedness = part == quadric_cap_zmin ? -1.0 : 1.0;
    s.error = 4.0 * double_epsilon * (glm::length(s.point) + size);
    return s;
  }
  const side_function side(q);
  s.point = project_to_side(side, approx_point);
  dvec3 g = side.gradient(s.point);
  double g_len = glm::length(g);
  // At the cone apex (and any other singular point) the gradient vanishes: use the axis.
  s.normal = side_normal(g, g_len);
  s.uv = side_uv(q, s.point);
  if (q.kind == quadric_kind::general) {
    // The box projection's dp/du ∝ (1, 0, −n_x/n_z) (y held fixed on the surface). Where the
    // surface turns vertical (n_z → 0) it degenerates; take x projected onto the tangent plane.
    const dvec3& n = s.normal;
    dvec3 t = n.z < 0.0 ? dvec3(-n.z, 0.0, n.x) : dvec3(n.z, 0.0, -n.x);
    if (!(glm::length(t) > 1e-6)) t = dvec3(1.0, 0.0, 0.0) - n.x * n;
    s.dpdu = glm::length(t) > 1e-6 ? glm::normalize(t) : azimuthal_tangent(dvec3(0.0, 1.0, 0.0), n);
    // The projection reads upright from +z: dp/du × (−dp/dv) ∝ n / n_z, so the frame is
    // right-handed where the surface faces +z and mirrored where it faces −z.
    s.handedness = s.normal.z < 0.0 ? -1.0 : 1.0;
  } else {
    // Every other kind: u runs counter-clockwise seen from outside and v away from +z (sphere,
    // axial kinds, outside of the torus) or outward (disk), so normal × dpdu is −dp/dv.
    s.dpdu = azimuthal_tangent(s.point, s.normal);
  }
  // Distance to the exact surface to first order: |F| / |∇F| after projection, doubled for the
  // second-order term, plus the rounding of the projection itself.
  const double residual = g_len > 0.0 ? std::abs(side.value(s.point)) / g_len : 0.0;
  s.error = 2.0 * residual + 8.0 * double_epsilon * (glm::length(s.point) + size);
  return s;
}

quadric_surface quadric_surface_of_hit(const instance& inst, const quadric& q, const ray& r, float t,
                                       uint32_t part) {
  return quadric_surface_at(q, part, object_hit_point(inst, r, t));
}

vec3 quadric_world_normal(const instance& inst, const quadric& q, const ray& r, float t, uint32_t part) {
  const dvec3 approx_point = object_hit_point(inst, r, t);
  dvec3 object_normal;
  if (is_cap(part)) {
    object_normal = dvec3(0.0, 0.0, part == quadric_cap_zmin ? -1.0 : 1.0);
  } else {
    const side_function side(q);
    const dvec3 g = side.gradient(project_to_side(side, approx_point));
    object_normal = side_normal(g, glm::length(g));
  }
  return vec3(glm::normalize(inst.world_from_object_normal * object_normal));
}

quadric_world_point quadric_world_hit(const instance& inst, const quadric& q, const ray& r, float t,
                                      uint32_t part) {
  // The world ray moves to object space in double: the same transform the intersector used.
  return quadric_world_point_of(inst, quadric_surface_of_hit(inst, q, r, t, part));
}

quadric_world_point quadric_world_point_of(const instance& inst, const quadric_surface& s) {
  const dmat3 linear(inst.world_from_object);
  const dmat3& abs_linear = inst.abs_linear;
  const dvec3 world = transform_point(inst.world_from_object, s.point);
  // Object-space error (distance from the surface, any direction) carried by |M|, plus the
  // rounding of the double transform, then the rounding of the result to float.
  const dvec3 world_error =
      abs_linear * dvec3(s.error) +
      8.0 * double_epsilon * (abs_linear * glm::abs(s.point) + glm::abs(dvec3(inst.world_from_object[3])));

  quadric_world_point w;
  w.point = vec3(world);
  w.error = vec3(world_error) + glm::abs(w.point) * (2.0f * machine_epsilon);
  w.normal = vec3(glm::normalize(inst.world_from_object_normal * s.normal));
  w.tangent = vec3(glm::normalize(linear * s.dpdu));
  // The normal matrix keeps the normal outward while M carries dpdu and dp/dv, so under a mirror
  // cross(normal, tangent) turns against M·(−dp/dv): det M < 0 flips the handedness.
  w.handedness = float(inst.mirrored ? -s.handedness : s.handedness);
  w.uv = vec2(s.uv);
  return w;
}

namespace {

// UV difference folded across the u seam (u wraps from 1 back to 0 around the axis).
dvec2 uv_difference(const dvec2& a, const dvec2& b) {
  dvec2 d = a - b;
  d.x -= std::round(d.x);
  return d;
}

}  // namespace

bool quadric_world_uv_jacobian(const instance& inst, const quadric& q, const ray& r, float t, uint32_t part,
                               vec3& dp_du, vec3& dp_dv) {
  return quadric_world_uv_jacobian(inst, q, part, quadric_surface_of_hit(inst, q, r, t, part), dp_du, dp_dv);
}

bool quadric_world_uv_jacobian(const instance& inst, const quadric& q, uint32_t part,
                               const quadric_surface& s, vec3& dp_du, vec3& dp_dv) {
  // Central differences of the parametric UV along two orthonormal tangents, at a step small
  // against the shape (its bounds) yet far above rounding: the UV change per unit tangent length.
  const dvec3 t1 = s.dpdu, t2 = glm::cross(s.normal, s.dpdu);
  const double h = 1e-4 * std::max(glm::length(q.bounds.diagonal()), 1e-12);
  const side_function side(q);
  const dvec2 du_dt1 =
      uv_difference(uv_at(side, part, s.point + h * t1), uv_at(side, part, s.point - h * t1)) / (2.0 * h);
  const dvec2 du_dt2 =
      uv_difference(uv_at(side, part, s.point + h * t2), uv_at(side, part, s.point - h * t2)) / (2.0 * h);
  // Invert [duv/dt1 duv/dt2] to get dp/du and dp/dv in the (t1, t2) frame.
  const double det = du_dt1.x * du_dt2.y - du_dt2.x * du_dt1.y;
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
  const dvec3 object_du = (du_dt2.y * t1 - du_dt1.y * t2) / det;
  const dvec3 object_dv = (du_dt1.x * t2 - du_dt2.x * t1) / det;
  const dmat3 linear(inst.world_from_object);
  dp_du = vec3(linear * object_du);
  dp_dv = vec3(linear * object_dv);
  return is_finite(dp_du) && is_finite(dp_dv);
}

float quadric_world_curvature(const instance& inst, const quadric& q, const ray& r, float t, uint32_t part) {
  return quadric_world_curvature(inst, q, part, quadric_surface_of_hit(inst, q, r, t, part));
}

quadric_normal_turns quadric_world_normal_turns(const instance& inst, const quadric& q, uint32_t part,
                                                const quadric_surface& s) {
  quadric_normal_turns out;
  const dvec3 tangents[2] = {s.dpdu, glm::cross(s.normal, s.dpdu)};
  if (is_cap(part) || q.kind == quadric_kind::disk) return out;  // planar
  if (q.kind != quadric_kind::torus) {
    // A quadric's Hessian is the constant 2A, so the world normal N·∇F / |N·∇F| turns along the
    // object tangent t at P·N·2A·t / |N·∇F| (P: the projection off the normal) while the point
    // moves M·t: the limit of central differences, without their four projections.
    const implicit_form f = implicit_of(q);
    const dvec3 g = inst.world_from_object_normal * implicit_gradient(f, s.point);
    const double g_len = glm::length(g);
    if (!(g_len > 0.0) || !std::isfinite(g_len)) return out;  // the cone's apex
    out.normal = g / g_len;
    for (int i = 0; i < 2; ++i) {
      const dvec3 dg = inst.world_from_object_normal * (2.0 * (f.a * tangents[i]));
      out.turn[i] = (dg - out.normal * glm::dot(out.normal, dg)) / g_len;
      out.step[i] = transform_vector(inst.world_from_object, tangents[i]);
    }
    out.valid = true;
    return out;
  }
  // The torus (quartic): central differences at a step small against the shape.
  const double h = 1e-4 * std::max(glm::length(q.bounds.diagonal()), 1e-12);
  const side_function side(q);
  out.normal = glm::normalize(inst.world_from_object_normal * s.normal);
  for (int i = 0; i < 2; ++i) {
    dvec3 a_point, a_normal, b_point, b_normal;
    point_and_normal_at(side, part, s.point + h * tangents[i], a_point, a_normal);
    point_and_normal_at(side, part, s.point - h * tangents[i], b_point, b_normal);
    out.turn[i] = glm::normalize(inst.world_from_object_normal * a_normal) -
                  glm::normalize(inst.world_from_object_normal * b_normal);
    out.step[i] = transform_vector(inst.world_from_object, a_point - b_point);
  }
  out.valid = true;
  return out;
}

float quadric_world_curvature(const instance& inst, const quadric& q, uint32_t part,
                              const quadric_surface& s) {
  const quadric_normal_turns turns = quadric_world_normal_turns(inst, q, part, s);
  if (!turns.valid) return 0.0f;
  double curvature = 0.0;
  for (int i = 0; i < 2; ++i) {
    const double distance = glm::length(turns.step[i]);
    if (distance > 0.0) curvature = std::max(curvature, glm::length(turns.turn[i]) / distance);
  }
  return std::isfinite(curvature) ? float(curvature) : 0.0f;
}

}  // namespace kiln
