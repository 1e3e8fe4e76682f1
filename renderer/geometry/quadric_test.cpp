// Analytic ray-quadric cases for every kind: through the centre, tangent, starting inside,
// parallel to the axis, cap edges, the cone apex, hits near tmin and tmax, clipped parts.
#include "geometry/quadric.h"

#include <gtest/gtest.h>

#include "geometry/quadric_test_util.h"

namespace kiln {
namespace {

using namespace kiln::testing;

std::optional<quadric_ray_hit> shoot(const quadric& q, dvec3 o, dvec3 d, double tmin = 0.0,
                                     double tmax = 1e30) {
  return intersect_quadric(q, o, d, tmin, tmax);
}

void expect_hit(const std::optional<quadric_ray_hit>& h, double t, uint32_t part, double tolerance = 1e-12) {
  ASSERT_TRUE(h.has_value());
  EXPECT_NEAR(h->t, t, tolerance);
  EXPECT_EQ(h->part, part);
}

TEST(quadric_sphere, centre_tangent_inside_and_extent) {
  const quadric s = make_sphere(1.0);
  expect_hit(shoot(s, {0, 0, -5}, {0, 0, 1}), 4.0, quadric_side);
  expect_hit(shoot(s, {0, 0, -5}, {0, 0, 2}), 2.0, quadric_side);  // t is in units of d
  expect_hit(shoot(s, {0, 0, 0}, {0, 0, 1}), 1.0, quadric_side);   // from inside: the far wall
  // Just inside the silhouette hits near the tangent point; just outside misses.
  auto graze = shoot(s, {1.0 - 1e-9, 0, -5}, {0, 0, 1});
  ASSERT_TRUE(graze.has_value());
  EXPECT_NEAR(graze->t, 5.0, 1e-4);
  EXPECT_FALSE(shoot(s, {1.0 + 1e-9, 0, -5}, {0, 0, 1}).has_value());
  // tmax just short of the hit misses; tmin past the near hit finds the far one.
  EXPECT_FALSE(shoot(s, {0, 0, -5}, {0, 0, 1}, 0.0, 3.999).has_value());
  expect_hit(shoot(s, {0, 0, -5}, {0, 0, 1}, 0.0, 4.001), 4.0, quadric_side);
  expect_hit(shoot(s, {0, 0, -5}, {0, 0, 1}, 4.001), 6.0, quadric_side);
  EXPECT_FALSE(shoot(s, {0, 0, -5}, {0, 0, -1}).has_value());  // pointing away
  // A hit 1e-7 ahead of the origin is found to full precision, not lost to an epsilon.
  expect_hit(shoot(s, {0, 0, -1.0 - 1e-7}, {0, 0, 1}), 1e-7, quadric_side, 1e-15);
}

TEST(quadric_cylinder, sides_caps_axis_parallel_and_clipping) {
  const quadric open = make_axial(quadric_kind::cylinder, 0.5, -1.0, 1.0, false);
  const quadric capped = make_axial(quadric_kind::cylinder, 0.5, -1.0, 1.0, true);
  expect_hit(shoot(open, {-5, 0, 0}, {1, 0, 0}), 4.5, quadric_side);
  // Parallel to the axis, inside the tube: the open one lets it through, caps stop it.
  EXPECT_FALSE(shoot(open, {0.1, 0, -5}, {0, 0, 1}).has_value());
  expect_hit(shoot(capped, {0.1, 0, -5}, {0, 0, 1}), 4.0, quadric_cap_zmin);
  expect_hit(shoot(capped, {0.1, 0, 5}, {0, 0, -1}), 4.0, quadric_cap_zmax);
  // Parallel and outside misses (a = 0 and no root).
  EXPECT_FALSE(shoot(capped, {0.6, 0, -5}, {0, 0, 1}).has_value());
  // Cap edge: just inside the rim hits the cap, just outside misses everything.
  expect_hit(shoot(capped, {0.5 - 1e-9, 0, -5}, {0, 0, 1}), 4.0, quadric_cap_zmin);
  EXPECT_FALSE(shoot(capped, {0.5 + 1e-9, 0, -5}, {0, 0, 1}).has_value());
  // Above zmax the tube is clipped away; a ray from there down through the open top hits the inside wall.
  EXPECT_FALSE(shoot(open, {-5, 0, 1.2}, {1, 0, 0}).has_value());
  expect_hit(shoot(open, {0, 0, 2}, {0.25, 0, -1}), 2.0, quadric_side, 1e-12);  // enters the top, hits x=0.5
  // From inside the capped solid the first hit is the far wall.
  expect_hit(shoot(capped, {0, 0, 0}, {1, 0, 0}), 0.5, quadric_side);
}

TEST(quadric_cone, apex_side_and_caps) {
  // Base radius 1 at z = 0, apex at z = 2.
  const quadric cone = make_axial(quadric_kind::cone, 1.0, 0.0, 2.0, true, 2.0);
  // Down the axis onto the apex: a double root at z = 2.
  expect_hit(shoot(cone, {0, 0, 5}, {0, 0, -1}), 3.0, quadric_side, 1e-9);
  quadric_surface apex = quadric_surface_at(cone, quadric_side, {0, 0, 2});
  EXPECT_TRUE(is_finite(apex.normal));
  EXPECT_NEAR(glm::length(apex.normal), 1.0, 1e-12);
  // At z = 1 the radius is 0.5.
  expect_hit(shoot(cone, {-5, 0, 1}, {1, 0, 0}), 4.5, quadric_side);
  // Up the axis from below: the base cap.
  expect_hit(shoot(cone, {0, 0, -3}, {0, 0, 1}), 3.0, quadric_cap_zmin);
  // The upper nappe of the double cone (z > 2) is clipped away.
  EXPECT_FALSE(shoot(cone, {-5, 0, 3}, {1, 0, 0}).has_value());
  // A frustum (zmax < height) has a top cap of radius 0.25 at z = 1.5.
  const quadric frustum = make_axial(quadric_kind::cone, 1.0, 0.0, 1.5, true, 2.0);
  expect_hit(shoot(frustum, {0.2, 0, 5}, {0, 0, -1}), 3.5, quadric_cap_zmax);
}

TEST(quadric_paraboloid, axis_vertex_cap_and_rim) {
  // x² + y² = z / 2 (radius 1 at zmax 2).
  const quadric open = make_axial(quadric_kind::paraboloid, 1.0, 0.0, 2.0, false);
  const quadric capped = make_axial(quadric_kind::paraboloid, 1.0, 0.0, 2.0, true);
  expect_hit(shoot(open, {0, 0, 5}, {0, 0, -1}), 5.0, quadric_side);  // into the bowl, onto the vertex
  expect_hit(shoot(open, {0, 0, -5}, {0, 0, 1}), 5.0, quadric_side);  // the vertex from below
  expect_hit(shoot(capped, {0, 0, 5}, {0, 0, -1}), 3.0, quadric_cap_zmax);
  // At z = 0.5 the radius is 0.5.
  expect_hit(shoot(open, {-5, 0, 0.5}, {1, 0, 0}), 4.5, quadric_side);
  quadric_surface vertex = quadric_surface_at(open, quadric_side, {0, 0, 0});
  EXPECT_NEAR(vertex.normal.z, -1.0, 1e-12);  // outward is down at the vertex
}

TEST(quadric_hyperboloids, waist_sheets_gap_and_caps) {
  const quadric one = make_axial(quadric_kind::hyperboloid_one_sheet, 0.5, -1.0, 1.0, false, 1.0, 0.8);
  expect_hit(shoot(one, {-5, 0, 0}, {1, 0, 0}), 4.5, quadric_side);  // the waist
  // Along the axis through the open throat: nothing.
  EXPECT_FALSE(shoot(one, {0, 0, -5}, {0, 0, 1}).has_value());
  const quadric two = make_axial(quadric_kind::hyperboloid_two_sheets, 0.5, -2.0, 2.0, false, 1.0, 0.8);
  const quadric two_capped = make_axial(quadric_kind::hyperboloid_two_sheets, 0.5, -2.0, 2.0, true, 1.0, 0.8);
  expect_hit(shoot(two, {0, 0, -5}, {0, 0, 1}), 4.2, quadric_side);  // lower sheet's vertex at z = −c
  expect_hit(shoot(two_capped, {0, 0, -5}, {0, 0, 1}), 3.0, quadric_cap_zmin);
  EXPECT_FALSE(shoot(two, {-5, 0, 0}, {1, 0, 0}).has_value());  // the gap between the sheets
}

TEST(quadric_disk, annulus) {
  const quadric disk = make_disk(1.0, 0.3);
  expect_hit(shoot(disk, {0.5, 0, 5}, {0, 0, -1}), 5.0, quadric_side);
  EXPECT_FALSE(shoot(disk, {0.2, 0, 5}, {0, 0, -1}).has_value());   // the hole
  EXPECT_FALSE(shoot(disk, {1.01, 0, 5}, {0, 0, -1}).has_value());  // beyond the rim
  EXPECT_FALSE(shoot(disk, {-5, 0, 0}, {1, 0, 0}).has_value());     // edge-on, in the plane
  quadric_surface s = quadric_surface_at(disk, quadric_side, {0.65, 0, 0});
  EXPECT_NEAR(s.uv.y, 0.5, 1e-12);
}

TEST(quadric_general, ellipsoid_from_coefficients_and_clip_box) {
  const quadric g = make_general_ellipsoid();  // centre (0.3, 0, 0), semi-axes 2, 1, 0.5; z ≤ 0.2
  expect_hit(shoot(g, {-5, 0, 0}, {1, 0, 0}), 3.3, quadric_side);
  // The top (z = 0.5) is clipped away: a ray down the centre passes the hole, hits the bottom from inside.
  expect_hit(shoot(g, {0.3, 0, 5}, {0, 0, -1}), 5.5, quadric_side);
  quadric_surface bottom = quadric_surface_at(g, quadric_side, {0.3, 0, -0.5});
  EXPECT_NEAR(bottom.normal.z, -1.0, 1e-12);
}

TEST(quadric_torus, equator_hole_top_and_grazing) {
  const quadric torus = make_torus(1.0, 0.3);
  expect_hit(shoot(torus, {-5, 0, 0}, {1, 0, 0}), 3.7, quadric_side, 1e-12);
  expect_hit(shoot(torus, {-5, 0, 0}, {1, 0, 0}, 3.8), 4.3, quadric_side, 1e-12);  // inner wall
  EXPECT_FALSE(shoot(torus, {0, 0, 5}, {0, 0, -1}).has_value());                   // the hole
  expect_hit(shoot(torus, {1, 0, 5}, {0, 0, -1}), 4.7, quadric_side, 1e-12);
  expect_hit(shoot(torus, {1, 0, 0}, {0, 0, -1}), 0.3, quadric_side, 1e-12);  // from inside the tube
  // Grazing the top of the tube: just below hits, just above misses.
  auto graze = shoot(torus, {-5, 0, 0.3 - 1e-9}, {1, 0, 0});
  ASSERT_TRUE(graze.has_value());
  EXPECT_NEAR(graze->t, 4.0, 1e-3);
  EXPECT_FALSE(shoot(torus, {-5, 0, 0.3 + 1e-9}, {1, 0, 0}).has_value());
  // Far away, the closest hit is still found to full precision.
  expect_hit(shoot(torus, {-1e6, 0, 0.1}, {1, 0, 0}), 1e6 - 1.0 - std::sqrt(0.09 - 0.01), quadric_side, 1e-9);
}

TEST(quadric_bounds, tight_for_every_kind) {
  EXPECT_EQ(quadric_bounds(make_sphere(2.0)).upper, dvec3(2.0));
  bounds3 cone = quadric_bounds(make_axial(quadric_kind::cone, 1.0, 0.5, 1.5, false, 2.0));
  EXPECT_DOUBLE_EQ(cone.upper.x, 0.75);  // radius at zmin = 0.5
  EXPECT_DOUBLE_EQ(cone.lower.z, 0.5);
  bounds3 hyper =
      quadric_bounds(make_axial(quadric_kind::hyperboloid_one_sheet, 0.5, -1.0, 2.0, false, 1.0, 1.0));
  EXPECT_DOUBLE_EQ(hyper.upper.x, 0.5 * std::sqrt(5.0));
  bounds3 torus = quadric_bounds(make_torus(1.0, 0.25));
  EXPECT_EQ(torus.upper, dvec3(1.25, 1.25, 0.25));
}

TEST(quadric_surface, uv_and_tangent_conventions) {
  const quadric s = make_sphere(2.0);
  quadric_surface north = quadric_surface_at(s, quadric_side, {0, 0, 2.1});
  EXPECT_NEAR(north.uv.y, 1.0, 1e-12);
  EXPECT_NEAR(glm::length(north.point), 2.0, 1e-15);  // projected onto the sphere
  quadric_surface side = quadric_surface_at(s, quadric_side, {0, 2, 0});
  EXPECT_NEAR(side.uv.x, 0.25, 1e-12);
  EXPECT_NEAR(side.uv.y, 0.5, 1e-12);
  EXPECT_NEAR(glm::dot(side.dpdu, dvec3(-1, 0, 0)), 1.0, 1e-12);
  const quadric torus = make_torus(1.0, 0.3);
  quadric_surface top = quadric_surface_at(torus, quadric_side, {0, 1, 0.3});
  EXPECT_NEAR(top.uv.x, 0.25, 1e-12);
  EXPECT_NEAR(top.uv.y, 0.25, 1e-12);
  EXPECT_NEAR(top.normal.z, 1.0, 1e-12);
}

}  // namespace
}  // namespace kiln
