// Precision sweep: a unit sphere seen from 1 to 1e7 away. The stated bound for kiln's solver:
// the hit o + t·d lies within 8·ε·D of the sphere (D the distance, ε double's epsilon: the
// rounding of evaluating o + t·d itself) and t agrees with a long-double reference to 4·ε·D.
// The textbook solver (b² − 4ac) fails that bound at every distance in float and from 1e2 in double
// (at 1e7 it is off the sphere by ~0.04 in double, by more than the radius in float),
// which shows the test can fail.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "geometry/quadric.h"
#include "geometry/quadric_test_util.h"

namespace kiln {
namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

// The textbook near root of |o + t·d|² = 1 with unit d, in precision T.
template <typename T>
T naive_sphere_t(const dvec3& o_in, const dvec3& d_in) {
  const T ox = T(o_in.x), oy = T(o_in.y), oz = T(o_in.z), dx = T(d_in.x), dy = T(d_in.y), dz = T(d_in.z);
  const T b = 2 * (ox * dx + oy * dy + oz * dz);
  const T c = ox * ox + oy * oy + oz * oz - 1;
  const T disc = b * b - 4 * c;
  return (-b - std::sqrt(std::max(disc, T(0)))) / 2;
}

// Reference: the closest-approach form in long double (64-bit significand).
long double reference_t(const dvec3& o, const dvec3& d) {
  const long double ox = o.x, oy = o.y, oz = o.z, dx = d.x, dy = d.y, dz = d.z;
  const long double tc = -(ox * dx + oy * dy + oz * dz);
  const long double px = ox + tc * dx, py = oy + tc * dy, pz = oz + tc * dz;
  return tc - std::sqrt(1.0L - (px * px + py * py + pz * pz));
}

double surface_error(const dvec3& o, const dvec3& d, double t) {
  return std::abs(glm::length(o + t * d) - 1.0);
}

struct sweep_result {
  double worst_kiln = 0.0, worst_kiln_t = 0.0, worst_float = 0.0, worst_double = 0.0;
  int rays = 0;
};

sweep_result sweep(double distance) {
  const quadric sphere = testing::make_sphere(1.0);
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  sweep_result r;
  for (int i = 0; i < 500; ++i) {
    dvec3 dir_out;
    do dir_out = dvec3(u(rng), u(rng), u(rng));
    while (glm::length(dir_out) < 0.1 || glm::length(dir_out) > 1.0);
    // Origins and directions are float-representable, as rays in the renderer are.
    const dvec3 o = dvec3(vec3(glm::normalize(dir_out) * distance));
    dvec3 target(u(rng), u(rng), u(rng));
    target *= 0.7;  // inside the sphere, up to near its silhouette
    const dvec3 d = glm::normalize(dvec3(vec3(glm::normalize(target - o))));
    std::optional<quadric_ray_hit> h = intersect_quadric(sphere, o, d, 0.0, 1e30);
    if (!h) continue;  // float-rounded directions can turn a near-silhouette ray into a miss
    ++r.rays;
    const double t_ref = double(reference_t(o, d));
    r.worst_kiln = std::max(r.worst_kiln, surface_error(o, d, h->t) / (eps * distance));
    r.worst_kiln_t = std::max(r.worst_kiln_t, std::abs(h->t - t_ref) / (eps * distance));
    r.worst_float =
        std::max(r.worst_float, surface_error(o, d, double(naive_sphere_t<float>(o, d))) / (eps * distance));
    r.worst_double =
        std::max(r.worst_double, surface_error(o, d, naive_sphere_t<double>(o, d)) / (eps * distance));
  }
  return r;
}

TEST(quadric_precision, sphere_from_one_to_ten_million) {
  for (double distance : {1.5, 10.0, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7}) {
    const sweep_result r = sweep(distance);
    ASSERT_GT(r.rays, 100) << distance;
    // Errors are in units of ε·D; the stated bound is 8 for the point and 4 for t.
    EXPECT_LE(r.worst_kiln, 8.0) << "distance " << distance;
    EXPECT_LE(r.worst_kiln_t, 4.0) << "distance " << distance;
    EXPECT_GT(r.worst_float, 8.0) << "naive float unexpectedly fine at " << distance;
    if (distance >= 1e2) {
      EXPECT_GT(r.worst_double, 8.0) << "naive double unexpectedly fine at " << distance;
    }
    std::printf("distance %8.0e: kiln %.2f eps*D (t %.2f), naive float %.3g eps*D, naive double %.3g eps*D\n",
                distance, r.worst_kiln, r.worst_kiln_t, r.worst_float, r.worst_double);
  }
}

}  // namespace
}  // namespace kiln
