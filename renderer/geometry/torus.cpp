// Ray-torus intersection: the quartic (|p|² + R² − r²)² − 4R²(x² + y²) = 0 along the ray.
// Why not the closed form (Ferrari/Cardano)? Its resolvent cubic cancels badly for grazing and
// far-away rays, which is exactly where tori show holes and speckles. Instead the ray is first
// re-centred on its closest approach to the torus centre and made unit length (coefficients of
// the torus' size), the search is limited to the part of the ray inside the bounding box, and the
// roots are isolated between the roots of the derivative (see polynomial.cpp): between two
// critical points the quartic is monotonic, so a sign change brackets exactly one root, which
// safeguarded Newton refines to full double precision. A root is missed only where the quartic
// touches zero without crossing it, i.e. an exactly tangent ray.
#include <cmath>

#include "geometry/polynomial.h"
#include "geometry/quadric.h"

namespace kiln {

torus_ray_quartic make_torus_quartic(double major_radius, double minor_radius, const dvec3& o,
                                     const dvec3& d) {
  // Unit direction and re-centred origin: s is the distance from oc, t = t_c + s / |d|.
  torus_ray_quartic out;
  out.length = glm::length(d);
  const dvec3 dn = d / out.length;
  out.t_c = -glm::dot(o, d) / (out.length * out.length);
  const dvec3 oc = o + out.t_c * d;

  const double big = major_radius * major_radius;
  const double od = glm::dot(oc, dn);
  const double k = glm::dot(oc, oc) + big - minor_radius * minor_radius;
  const double dxy = dn.x * dn.x + dn.y * dn.y;
  const double oxy_d = oc.x * dn.x + oc.y * dn.y;
  const double oxy = oc.x * oc.x + oc.y * oc.y;
  // (s² + 2·od·s + k)² − 4R²(dxy·s² + 2·oxy_d·s + oxy), with |dn| = 1.
  out.coefficients[0] = k * k - 4.0 * big * oxy;
  out.coefficients[1] = 4.0 * od * k - 8.0 * big * oxy_d;
  out.coefficients[2] = 4.0 * od * od + 2.0 * k - 4.0 * big * dxy;
  out.coefficients[3] = 4.0 * od;
  out.coefficients[4] = 1.0;
  return out;
}

std::optional<double> intersect_torus(double major_radius, double minor_radius, const dvec3& o,
                                      const dvec3& d, double tmin, double tmax) {
  const double outer = major_radius + minor_radius;
  bounds3 box{dvec3(-outer, -outer, -minor_radius), dvec3(outer, outer, minor_radius)};
  // A little padding so that rounding in the slab test never cuts off a silhouette hit.
  const dvec3 pad(1e-9 * outer);
  box.lower -= pad;
  box.upper += pad;
  double t_enter = tmin, t_exit = tmax;
  if (!clip_ray_to_box(box, o, d, t_enter, t_exit)) return std::nullopt;

  const torus_ray_quartic quartic = make_torus_quartic(major_radius, minor_radius, o, d);
  const double s_lo = (t_enter - quartic.t_c) * quartic.length,
               s_hi = (t_exit - quartic.t_c) * quartic.length;
  const polynomial_roots roots = polynomial_roots_in(quartic.coefficients, 4, s_lo, s_hi);
  for (int i = 0; i < roots.count; ++i) {
    const double t = quartic.t_c + roots.values[size_t(i)] / quartic.length;
    if (t > tmin && t < tmax) return t;
  }
  return std::nullopt;
}

}  // namespace kiln
