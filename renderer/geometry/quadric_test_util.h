// Test helpers: quadric definitions of every kind with bounds filled, as the loader makes them.
#pragma once

#include <vector>

#include "geometry/quadric.h"

namespace kiln::testing {

inline quadric finish(quadric q) {
  q.bounds = quadric_bounds(q);
  return q;
}

inline quadric make_sphere(double r) {
  quadric q;
  q.kind = quadric_kind::sphere;
  q.radius = r;
  return finish(q);
}

inline quadric make_axial(quadric_kind kind, double r, double zmin, double zmax, bool caps,
                          double height = 1.0, double c = 1.0) {
  quadric q;
  q.kind = kind;
  q.radius = r;
  q.zmin = zmin;
  q.zmax = zmax;
  q.caps = caps;
  q.height = height;
  q.c = c;
  return finish(q);
}

inline quadric make_disk(double r, double inner) {
  quadric q;
  q.kind = quadric_kind::disk;
  q.radius = r;
  q.inner_radius = inner;
  return finish(q);
}

inline quadric make_torus(double major, double minor) {
  quadric q;
  q.kind = quadric_kind::torus;
  q.major_radius = major;
  q.radius = minor;
  return finish(q);
}

// A general quadric: the ellipsoid x²/4 + y² + z²/0.25 = 1 written with all ten coefficients,
// shifted by (0.3, 0, 0) so the linear terms are non-zero, clipped to z ≤ 0.2.
inline quadric make_general_ellipsoid() {
  quadric q;
  q.kind = quadric_kind::general;
  // (x − 0.3)²/4 + y² + 4z² − 1 = 0.25x² + y² + 4z² − 0.15x + 0.0225 − 1
  const double k[10] = {0.25, 1.0, 4.0, 0.0, 0.0, 0.0, -0.15, 0.0, 0.0, 0.0225 - 1.0};
  for (int i = 0; i < 10; ++i) q.coefficients[i] = k[i];
  q.box.lower = dvec3(-2.0, -1.5, -1.0);
  q.box.upper = dvec3(2.5, 1.5, 0.2);
  return finish(q);
}

// One of each kind, for property tests.
inline std::vector<quadric> every_kind() {
  return {make_sphere(1.0),
          make_axial(quadric_kind::cylinder, 0.7, -1.0, 1.5, true),
          make_axial(quadric_kind::cylinder, 0.7, -1.0, 1.5, false),
          make_axial(quadric_kind::cone, 1.0, 0.0, 2.0, true, 2.0),
          make_axial(quadric_kind::cone, 1.0, 0.5, 1.5, true, 2.0),
          make_axial(quadric_kind::paraboloid, 1.0, 0.0, 2.0, true),
          make_axial(quadric_kind::hyperboloid_one_sheet, 0.5, -1.0, 1.0, true, 1.0, 0.8),
          make_axial(quadric_kind::hyperboloid_two_sheets, 0.5, -2.0, 2.0, true, 1.0, 0.8),
          make_disk(1.0, 0.3),
          make_general_ellipsoid(),
          make_torus(1.0, 0.3)};
}

}  // namespace kiln::testing
