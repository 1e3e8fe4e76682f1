// Analytic ray-quadric cases for every kind: through the centre, tangent, starting inside,
// parallel to the axis, cap edges, the cone apex, hits near tmin and tmax, clipped parts.
#include "geometry/quadric.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

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

// Every surface point a dense sweep of axis-parallel rays finds (all hits along each ray, from all
// six sides) lies inside the bounds, and every face of the bounds is touched by some point to
// within 1e-3 of the primitive's size: the bounds contain the primitive and are tight.
TEST(quadric_bounds, contain_every_swept_surface_point_and_touch_every_face) {
  const int n = 301;  // odd: the grid includes the centre lines
  for (const quadric& q : every_kind()) {
    SCOPED_TRACE("kind " + std::to_string(int(q.kind)));
    const bounds3 b = quadric_bounds(q);
    const dvec3 ext = b.diagonal();
    const double size = glm::length(ext);
    dvec3 seen_lo(1e30), seen_hi(-1e30);
    int hits = 0, outside = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      for (double dir : {1.0, -1.0}) {
        dvec3 d(0.0);
        d[axis] = dir;
        for (int i = 0; i < n; ++i) {
          for (int j = 0; j < n; ++j) {
            dvec3 o;
            o[a1] = b.lower[a1] + ext[a1] * i / (n - 1);
            o[a2] = b.lower[a2] + ext[a2] * j / (n - 1);
            o[axis] = dir > 0.0 ? b.lower[axis] - 1.0 : b.upper[axis] + 1.0;
            double tmin = 0.0;
            for (int k = 0; k < 8; ++k) {
              const auto h = shoot(q, o, d, tmin);
              if (!h) break;
              const dvec3 p = o + h->t * d;
              ++hits;
              seen_lo = glm::min(seen_lo, p);
              seen_hi = glm::max(seen_hi, p);
              const double slack = 1e-9 * size;
              if (glm::any(glm::lessThan(p, b.lower - slack)) ||
                  glm::any(glm::greaterThan(p, b.upper + slack)))
                ++outside;
              tmin = h->t;
            }
          }
        }
      }
    }
    EXPECT_GT(hits, 1000);
    EXPECT_EQ(outside, 0);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_LE(seen_lo[axis] - b.lower[axis], 1e-3 * size) << "axis " << axis << " lower face untouched";
      EXPECT_LE(b.upper[axis] - seen_hi[axis], 1e-3 * size) << "axis " << axis << " upper face untouched";
    }
  }
}

TEST(quadric_bounds, general_ellipsoid_is_cut_to_its_analytic_extent) {
  // Centre (0.3, 0, 0), semi-axes 2, 1, 0.5, in the box [−2, 2.5]×[−1.5, 1.5]×[−1, 0.2].
  const bounds3 b = quadric_bounds(make_general_ellipsoid());
  EXPECT_NEAR(b.lower.x, -1.7, 1e-12);
  EXPECT_NEAR(b.upper.x, 2.3, 1e-12);
  EXPECT_NEAR(b.lower.y, -1.0, 1e-12);
  EXPECT_NEAR(b.upper.y, 1.0, 1e-12);
  EXPECT_NEAR(b.lower.z, -0.5, 1e-12);
  EXPECT_EQ(b.upper.z, 0.2);  // the clip plane
  // The same ellipsoid with all signs flipped (F > 0 inside) has the same extent.
  quadric flipped = make_general_ellipsoid();
  for (double& k : flipped.coefficients) k = -k;
  const bounds3 f = quadric_bounds(flipped);
  EXPECT_NEAR(f.lower.x, -1.7, 1e-12);
  EXPECT_NEAR(f.upper.y, 1.0, 1e-12);
  // An unbounded general quadric (the cylinder x² + y² = 1) keeps its clip box.
  quadric cylinder = make_general_ellipsoid();
  const double k[10] = {1, 1, 0, 0, 0, 0, 0, 0, 0, -1};
  std::copy(k, k + 10, cylinder.coefficients);
  const bounds3 c = quadric_bounds(cylinder);
  EXPECT_EQ(c.lower, cylinder.box.lower);
  EXPECT_EQ(c.upper, cylinder.box.upper);
}

// One analytic ray case: the ray, its t range and the expected closest hit (or a miss).
struct ray_case {
  std::string name;
  quadric q;
  dvec3 o, d;
  bool hit = true;
  double t = 0.0;
  uint32_t part = quadric_side;
  double tolerance = 1e-12;
  double tmin = 0.0, tmax = 1e30;
};

constexpr double nudge = 1e-9;

// A hit at t (unit d), with the cases it implies: the same ray started 1e-7 before the surface
// hits at t = 1e-7 to full precision (no epsilon swallows it), and tmax just short of t misses
// while tmax just past it hits.
void add_hit_family(std::vector<ray_case>& cases, const std::string& name, const quadric& q, dvec3 o, dvec3 d,
                    double t, uint32_t part) {
  cases.push_back({name, q, o, d, true, t, part});
  cases.push_back(
      {name + ", origin 1e-7 before the surface", q, o + (t - 1e-7) * d, d, true, 1e-7, part, 1e-13});
  cases.push_back({name + ", tmax = t - 1e-9", q, o, d, false, 0, 0, 0, 0.0, t - nudge});
  cases.push_back({name + ", tmax = t + 1e-9", q, o, d, true, t, part, 1e-12, 0.0, t + nudge});
}

// A horizontal ray along +y in the plane z, tangent to the cross-section circle of radius rho:
// 1e-9 inside it hits next to the tangent point (the chord is ~√(2ρ·1e-9) long), outside misses.
void add_tangent_pair(std::vector<ray_case>& cases, const std::string& name, const quadric& q, double z,
                      double rho) {
  cases.push_back(
      {name + ", tangent 1e-9 inside", q, {rho - nudge, -5, z}, {0, 1, 0}, true, 5.0, quadric_side, 1e-4});
  cases.push_back({name + ", tangent 1e-9 outside", q, {rho + nudge, -5, z}, {0, 1, 0}, false});
}

// A ray along −z (from_above) or +z at radius rho just inside (hits the cap at t) and just outside
// the cap's rim (outside_hit: whether it then meets the side, next to the rim).
void add_rim_pair(std::vector<ray_case>& cases, const std::string& name, const quadric& q, uint32_t cap,
                  double t, bool outside_hit) {
  const double z0 = cap == quadric_cap_zmin ? q.zmin : q.zmax;
  const double rho = quadric_radius_at(q, z0);
  const double dz = cap == quadric_cap_zmin ? 1.0 : -1.0;
  const dvec3 start(0, 0, z0 - dz * t);
  cases.push_back(
      {name + ", rim 1e-9 inside", q, start + dvec3(rho - nudge, 0, 0), {0, 0, dz}, true, t, cap});
  cases.push_back({name + ", rim 1e-9 outside",
                   q,
                   start + dvec3(rho + nudge, 0, 0),
                   {0, 0, dz},
                   outside_hit,
                   t,
                   quadric_side,
                   1e-8});
}

// A ray along +x from x = −5 in the plane z = zmax ± 1e-9: above, the clipped-away part (which
// the unclipped surface would have) is not hit; below, the side is hit at t.
void add_clip_pair(std::vector<ray_case>& cases, const std::string& name, const quadric& q, double zmax,
                   double t) {
  cases.push_back({name + ", 1e-9 above the clip", q, {-5, 0, zmax + nudge}, {1, 0, 0}, false});
  cases.push_back(
      {name + ", 1e-9 below the clip", q, {-5, 0, zmax - nudge}, {1, 0, 0}, true, t, quadric_side, 1e-8});
}

std::vector<ray_case> analytic_cases() {
  std::vector<ray_case> c;
  const quadric sphere = make_sphere(1.0);
  add_hit_family(c, "sphere", sphere, {0, 0, -5}, {0, 0, 1}, 4.0, quadric_side);
  add_tangent_pair(c, "sphere", sphere, 0.0, 1.0);
  c.push_back({"sphere, origin inside", sphere, {0, 0, 0}, {1, 0, 0}, true, 1.0});

  const quadric cyl = make_axial(quadric_kind::cylinder, 0.5, -1.0, 1.0, true);
  const quadric open_cyl = make_axial(quadric_kind::cylinder, 0.5, -1.0, 1.0, false);
  add_hit_family(c, "cylinder", cyl, {-5, 0, 0}, {1, 0, 0}, 4.5, quadric_side);
  add_hit_family(c, "cylinder zmin cap", cyl, {0.1, 0, -5}, {0, 0, 1}, 4.0, quadric_cap_zmin);
  add_hit_family(c, "cylinder zmax cap", cyl, {0.1, 0, 5}, {0, 0, -1}, 4.0, quadric_cap_zmax);
  add_tangent_pair(c, "cylinder", cyl, 0.0, 0.5);
  add_rim_pair(c, "cylinder zmin cap", cyl, quadric_cap_zmin, 4.0, false);
  add_rim_pair(c, "cylinder zmax cap", cyl, quadric_cap_zmax, 4.0, false);
  add_clip_pair(c, "cylinder", cyl, 1.0, 4.5);
  add_clip_pair(c, "open cylinder", open_cyl, 1.0, 4.5);
  c.push_back({"cylinder, origin inside", cyl, {0, 0, 0}, {1, 0, 0}, true, 0.5});
  c.push_back(
      {"cylinder, origin inside, up the axis", cyl, {0, 0, 0}, {0, 0, 1}, true, 1.0, quadric_cap_zmax});

  const quadric cone = make_axial(quadric_kind::cone, 1.0, 0.0, 2.0, true, 2.0);  // apex at z = 2
  const quadric frustum = make_axial(quadric_kind::cone, 1.0, 0.5, 1.5, true, 2.0);
  add_hit_family(c, "cone", cone, {-5, 0, 1}, {1, 0, 0}, 4.5, quadric_side);
  add_hit_family(c, "cone base", cone, {0, 0, -3}, {0, 0, 1}, 3.0, quadric_cap_zmin);
  add_hit_family(c, "frustum top", frustum, {0.2, 0, 5}, {0, 0, -1}, 3.5, quadric_cap_zmax);
  add_tangent_pair(c, "cone", cone, 1.0, 0.5);
  add_rim_pair(c, "cone base", cone, quadric_cap_zmin, 5.0, false);
  add_rim_pair(c, "frustum base", frustum, quadric_cap_zmin, 5.0, false);
  add_rim_pair(c, "frustum top", frustum, quadric_cap_zmax, 3.5, true);  // then the widening side
  add_clip_pair(c, "cone (upper nappe)", cone, 2.0, 5.0);
  add_clip_pair(c, "frustum", frustum, 1.5, 4.75);
  c.push_back({"cone, origin inside", cone, {0, 0, 0.5}, {1, 0, 0}, true, 0.75});

  // x² + y² = z / 2: radius 1 at zmax = 2.
  const quadric parab = make_axial(quadric_kind::paraboloid, 1.0, 0.0, 2.0, true);
  add_hit_family(c, "paraboloid", parab, {-5, 0, 0.5}, {1, 0, 0}, 4.5, quadric_side);
  add_hit_family(c, "paraboloid cap", parab, {0, 0, 5}, {0, 0, -1}, 3.0, quadric_cap_zmax);
  add_tangent_pair(c, "paraboloid", parab, 0.5, 0.5);
  add_rim_pair(c, "paraboloid cap", parab, quadric_cap_zmax, 3.0, false);
  add_clip_pair(c, "paraboloid", parab, 2.0, 4.0);
  c.push_back({"paraboloid, origin inside", parab, {0, 0, 1}, {1, 0, 0}, true, std::sqrt(0.5)});

  const quadric hyp1 = make_axial(quadric_kind::hyperboloid_one_sheet, 0.5, -1.0, 1.0, true, 1.0, 0.8);
  const double hyp1_rim = 0.5 * std::sqrt(1.0 + 1.0 / 0.64);
  add_hit_family(c, "hyperboloid 1", hyp1, {-5, 0, 0}, {1, 0, 0}, 4.5, quadric_side);
  add_hit_family(c, "hyperboloid 1 zmin cap", hyp1, {0, 0, -5}, {0, 0, 1}, 4.0, quadric_cap_zmin);
  add_tangent_pair(c, "hyperboloid 1", hyp1, 0.5, 0.5 * std::sqrt(1.0 + 0.25 / 0.64));
  add_rim_pair(c, "hyperboloid 1 zmin cap", hyp1, quadric_cap_zmin, 4.0, false);
  add_rim_pair(c, "hyperboloid 1 zmax cap", hyp1, quadric_cap_zmax, 4.0, false);
  add_clip_pair(c, "hyperboloid 1", hyp1, 1.0, 5.0 - hyp1_rim);
  c.push_back({"hyperboloid 1, origin inside", hyp1, {0, 0, 0}, {0, 1, 0}, true, 0.5});

  const quadric hyp2 = make_axial(quadric_kind::hyperboloid_two_sheets, 0.5, -2.0, 2.0, true, 1.0, 0.8);
  const double hyp2_rim = 0.5 * std::sqrt(4.0 / 0.64 - 1.0), rho16 = 0.5 * std::sqrt(3.0);
  add_hit_family(c, "hyperboloid 2", hyp2, {-5, 0, 1.6}, {1, 0, 0}, 5.0 - rho16, quadric_side);
  add_hit_family(c, "hyperboloid 2 zmin cap", hyp2, {0, 0, -5}, {0, 0, 1}, 3.0, quadric_cap_zmin);
  add_tangent_pair(c, "hyperboloid 2", hyp2, 1.6, rho16);
  add_rim_pair(c, "hyperboloid 2 zmin cap", hyp2, quadric_cap_zmin, 3.0, false);
  add_rim_pair(c, "hyperboloid 2 zmax cap", hyp2, quadric_cap_zmax, 3.0, false);
  add_clip_pair(c, "hyperboloid 2", hyp2, 2.0, 5.0 - hyp2_rim);
  c.push_back({"hyperboloid 2, origin inside", hyp2, {0, 0, 1.6}, {1, 0, 0}, true, rho16});

  const quadric disk = make_disk(1.0, 0.3);
  add_hit_family(c, "disk", disk, {0.5, 0, 5}, {0, 0, -1}, 5.0, quadric_side);
  c.push_back({"disk, rim 1e-9 inside", disk, {1.0 - nudge, 0, 5}, {0, 0, -1}, true, 5.0});
  c.push_back({"disk, rim 1e-9 outside", disk, {1.0 + nudge, 0, 5}, {0, 0, -1}, false});
  c.push_back({"disk, hole rim 1e-9 outside", disk, {0.3 + nudge, 0, 5}, {0, 0, -1}, true, 5.0});
  c.push_back({"disk, hole rim 1e-9 inside", disk, {0.3 - nudge, 0, 5}, {0, 0, -1}, false});

  // Centre (0.3, 0, 0), semi-axes 2, 1, 0.5, clipped to z ≤ 0.2 (half-width 2·√0.84 there).
  const quadric general = make_general_ellipsoid();
  add_hit_family(c, "general", general, {-5, 0, 0}, {1, 0, 0}, 3.3, quadric_side);
  c.push_back({"general, tangent 1e-9 inside",
               general,
               {-5, 1.0 - nudge, 0},
               {1, 0, 0},
               true,
               5.3,
               quadric_side,
               1e-4});
  c.push_back({"general, tangent 1e-9 outside", general, {-5, 1.0 + nudge, 0}, {1, 0, 0}, false});
  add_clip_pair(c, "general", general, 0.2, 5.3 - 2.0 * std::sqrt(0.84));
  c.push_back({"general, origin inside", general, {0.3, 0, 0}, {1, 0, 0}, true, 2.0});

  const quadric torus = make_torus(1.0, 0.3);
  add_hit_family(c, "torus", torus, {-5, 0, 0}, {1, 0, 0}, 3.7, quadric_side);
  add_tangent_pair(c, "torus (outer equator)", torus, 0.0, 1.3);
  c.push_back({"torus, origin inside", torus, {1, 0, 0}, {0, 0, 1}, true, 0.3});
  return c;
}

TEST(quadric_analytic, table_of_rim_tangent_inside_near_surface_tmax_and_clip_cases) {
  for (const ray_case& rc : analytic_cases()) {
    SCOPED_TRACE(rc.name);
    const auto h = shoot(rc.q, rc.o, rc.d, rc.tmin, rc.tmax);
    if (!rc.hit) {
      EXPECT_FALSE(h.has_value()) << "t " << (h ? h->t : 0.0) << " part " << (h ? h->part : 0u);
      continue;
    }
    expect_hit(h, rc.t, rc.part, rc.tolerance);
  }
}

// The documented UV and tangent handedness of every kind and part (docs/quadrics.md): v = 0 at the
// image's top, which is +z on the sphere, the axial kinds and the outside of the torus.
struct uv_case {
  std::string name;
  quadric q;
  uint32_t part;
  dvec3 point;
  double u, v, handedness;
};

TEST(quadric_surface, uv_and_handedness_of_every_kind_and_part) {
  const quadric sphere = make_sphere(2.0);
  const quadric cyl = make_axial(quadric_kind::cylinder, 0.5, -1.0, 1.0, true);
  const quadric cone = make_axial(quadric_kind::cone, 1.0, 0.0, 2.0, true, 2.0);
  const quadric parab = make_axial(quadric_kind::paraboloid, 1.0, 0.0, 2.0, true);
  const quadric hyp1 = make_axial(quadric_kind::hyperboloid_one_sheet, 0.5, -1.0, 1.0, true, 1.0, 0.8);
  const quadric hyp2 = make_axial(quadric_kind::hyperboloid_two_sheets, 0.5, -2.0, 2.0, true, 1.0, 0.8);
  const quadric disk = make_disk(1.0, 0.3);
  const quadric general = make_general_ellipsoid();  // box x ∈ [−2, 2.5], y ∈ [−1.5, 1.5]
  const quadric torus = make_torus(1.0, 0.3);
  const std::vector<uv_case> cases = {
      {"sphere north pole (projected)", sphere, quadric_side, {0, 0, 2.1}, 0.0, 0.0, 1},
      {"sphere equator +y", sphere, quadric_side, {0, 2, 0}, 0.25, 0.5, 1},
      {"sphere equator -x", sphere, quadric_side, {-2, 0, 0}, 0.5, 0.5, 1},
      {"sphere 45° south, -y", sphere, quadric_side, {0, -std::sqrt(2.0), -std::sqrt(2.0)}, 0.75, 0.75, 1},
      {"cylinder top rim +y", cyl, quadric_side, {0, 0.5, 1}, 0.25, 0.0, 1},
      {"cylinder bottom rim -x", cyl, quadric_side, {-0.5, 0, -1}, 0.5, 1.0, 1},
      {"cylinder z = 0.5", cyl, quadric_side, {0.5, 0, 0.5}, 0.0, 0.25, 1},
      {"cylinder zmax cap", cyl, quadric_cap_zmax, {0.25, 0, 1}, 0.0, 0.5, 1},
      {"cylinder zmin cap", cyl, quadric_cap_zmin, {0, -0.25, -1}, 0.75, 0.5, -1},
      {"cone z = 1", cone, quadric_side, {0, -0.5, 1}, 0.75, 0.5, 1},
      {"cone base cap rim", cone, quadric_cap_zmin, {-1, 0, 0}, 0.5, 1.0, -1},
      {"paraboloid z = 0.5", parab, quadric_side, {0.5, 0, 0.5}, 0.0, 0.75, 1},
      {"paraboloid cap", parab, quadric_cap_zmax, {0, 0.5, 2}, 0.25, 0.5, 1},
      {"hyperboloid 1 waist", hyp1, quadric_side, {0, 0.5, 0}, 0.25, 0.5, 1},
      {"hyperboloid 1 z = 0.8", hyp1, quadric_side, {-0.5 * std::sqrt(2.0), 0, 0.8}, 0.5, 0.1, 1},
      {"hyperboloid 2 upper sheet", hyp2, quadric_side, {0, 0.5 * std::sqrt(3.0), 1.6}, 0.25, 0.1, 1},
      {"hyperboloid 2 lower vertex", hyp2, quadric_side, {0, 0, -0.8}, 0.0, 0.7, 1},
      {"disk mid annulus", disk, quadric_side, {0.65, 0, 0}, 0.0, 0.5, 1},
      {"disk rim -y", disk, quadric_side, {0, -1, 0}, 0.75, 1.0, 1},
      {"general +y equator", general, quadric_side, {0.3, 1, 0}, 2.3 / 4.5, 0.5 / 3.0, 1},
      {"general bottom", general, quadric_side, {0.3, 0, -0.5}, 2.3 / 4.5, 0.5, -1},
      {"torus outer equator", torus, quadric_side, {1.3, 0, 0}, 0.0, 0.0, 1},
      {"torus top", torus, quadric_side, {0, 1, 0.3}, 0.25, 0.75, 1},
      {"torus inner equator", torus, quadric_side, {-0.7, 0, 0}, 0.5, 0.5, 1},
      {"torus bottom", torus, quadric_side, {0, -1, -0.3}, 0.75, 0.25, 1},
  };
  for (const uv_case& c : cases) {
    SCOPED_TRACE(c.name);
    const quadric_surface s = quadric_surface_at(c.q, c.part, c.point);
    EXPECT_NEAR(s.uv.x, c.u, 1e-12);
    EXPECT_NEAR(s.uv.y, c.v, 1e-12);
    EXPECT_EQ(s.handedness, c.handedness);
    EXPECT_NEAR(glm::dot(s.dpdu, s.normal), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(s.dpdu), 1.0, 1e-12);
  }
  // Tangent along increasing u (counter-clockwise about +z) and the projection onto the sphere.
  const quadric_surface side = quadric_surface_at(sphere, quadric_side, {0, 2, 0});
  EXPECT_NEAR(glm::dot(side.dpdu, dvec3(-1, 0, 0)), 1.0, 1e-12);
  EXPECT_NEAR(glm::length(quadric_surface_at(sphere, quadric_side, {0, 0, 2.1}).point), 2.0, 1e-15);
  EXPECT_NEAR(quadric_surface_at(torus, quadric_side, {0, 1, 0.3}).normal.z, 1.0, 1e-12);
}

}  // namespace
}  // namespace kiln
