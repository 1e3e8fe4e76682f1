// A glass ball (analytic KILN_quadric sphere, ior 1.5, a volume) in front of an unlit pattern
// plane, rendered through the Embree backend and Whitted shading, against ray optics written
// here: a double-precision tracer of the same sphere and plane with Snell's law and the exact
// unpolarised Fresnel equations at every crossing, summing the internally reflected paths. The
// plane's radiance is an affine function of position (vertex colours, which triangles
// interpolate exactly), so the radiance a ray brings back reveals where it landed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include "accel/embree/embree_accelerator.h"
#include "geometry/quadric_test_util.h"
#include "shade/whitted.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

constexpr double ball_radius = 1.0;
constexpr double glass_ior = 1.5;
constexpr double plane_half_size = 50.0;
constexpr double slope = 0.009;  // pattern change per unit of x (red) and y (green)

// The plane's radiance at (x, y): red and green record the landing point, blue is 1 so that it
// sums the weights of every path that reaches the plane.
dvec3 pattern(double x, double y) { return {0.5 + slope * x, 0.5 + slope * y, 1.0}; }

// The scene: the ball at the origin, the pattern plane at z = plane_z facing the camera (+z).
scene ball_in_front_of_pattern(double plane_z) {
  scene s;
  material glass;
  glass.metallic_factor = 0.0f;
  glass.roughness_factor = 0.0f;
  glass.transmission_factor = 1.0f;
  glass.ior = float(glass_ior);
  glass.thickness_factor = 1.0f;
  material plane;
  plane.unlit = true;
  s.materials = {glass, plane};

  s.quadrics.push_back(testing::make_sphere(ball_radius));
  instance ball;
  ball.kind = shape_kind::quadric;
  ball.shape = 0;
  ball.material = 0;
  finish_instance_transform(ball);
  s.instances.push_back(ball);

  mesh m;
  const double h = plane_half_size;
  for (dvec2 corner : {dvec2(-h, -h), dvec2(h, -h), dvec2(h, h), dvec2(-h, h)}) {
    m.positions.push_back(vec3(dvec3(corner, plane_z)));
    m.colors0.push_back(vec4(vec3(pattern(corner.x, corner.y)), 1.0f));
  }
  m.indices = {0, 1, 2, 0, 2, 3};
  testing::add_mesh_instance(s, std::move(m), 1);
  return s;
}

// --- The independent reference: geometric optics in double precision. ---

// Reflectance of an interface from index n1 into n2 at incidence cosine cos_i (unpolarised
// average of the s and p amplitudes), 1 beyond the critical angle.
double fresnel_reflectance(double cos_i, double n1, double n2) {
  const double sin_t = n1 / n2 * std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
  if (sin_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
  const double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
  const double rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

// Far or near root of |o + t d|² = R² beyond a small epsilon; none when the line misses.
std::optional<double> sphere_distance(const dvec3& o, const dvec3& d, bool from_inside) {
  const double b = glm::dot(o, d), c = glm::dot(o, o) - ball_radius * ball_radius;
  const double disc = b * b - c;
  if (disc < 0.0) return std::nullopt;
  const double t = from_inside ? -b + std::sqrt(disc) : -b - std::sqrt(disc);
  if (t > 1e-9) return t;
  return std::nullopt;
}

struct optics {
  double plane_z;
  int max_depth;  // the renderer's: a ray at this depth is shaded without further rays

  // Called for each path that reaches the plane, with its weight and landing point.
  std::function<void(double weight, const dvec2& landing)> on_landing = [](double, const dvec2&) {};

  // Radiance along o + t d; weight is the path's product of Fresnel factors so far.
  dvec3 trace(const dvec3& o, const dvec3& d, bool inside, int depth, double weight) const {
    const std::optional<double> to_ball = sphere_distance(o, d, inside);
    if (!to_ball) {
      const double t = d.z < 0.0 ? (plane_z - o.z) / d.z : -1.0;
      const dvec3 p = o + t * d;
      if (t <= 0.0 || std::abs(p.x) > plane_half_size || std::abs(p.y) > plane_half_size)
        return dvec3(0.0);  // the black environment
      on_landing(weight, dvec2(p));
      return pattern(p.x, p.y);
    }
    if (depth >= max_depth) return dvec3(0.0);  // glass emits nothing
    const dvec3 p = o + *to_ball * d;
    const dvec3 n = inside ? -p / ball_radius : p / ball_radius;  // faces the incoming ray
    const double n1 = inside ? glass_ior : 1.0, n2 = inside ? 1.0 : glass_ior;
    const double cos_i = -glm::dot(d, n);
    const double f = fresnel_reflectance(cos_i, n1, n2);
    dvec3 radiance = f * trace(p, d + 2.0 * cos_i * n, inside, depth + 1, weight * f);
    if (f < 1.0) {
      const double eta = n1 / n2;
      const double cos_t = std::sqrt(1.0 - eta * eta * (1.0 - cos_i * cos_i));
      const dvec3 refracted = eta * d + (eta * cos_i - cos_t) * n;
      radiance += (1.0 - f) * trace(p, refracted, !inside, depth + 1, weight * (1.0 - f));
    }
    return radiance;
  }
};

// The renderer's radiance along one camera ray: every ray traced down to max_depth.
vec3 rendered(const scene& s, const ray& camera, int max_depth) {
  embree_accelerator accel(s);
  shading_options options;
  options.max_depth = max_depth;
  options.min_throughput = 0.0f;
  shading_context ctx{s, accel, options, scene_has_see_through(s)};
  ray_counts counts;
  return trace_radiance(ctx, camera, path_state{}, counts);
}

// Where the plane is hit along the most heavily weighted path (the twice-refracted one).
dvec2 main_landing(const optics& o, const dvec3& origin, const dvec3& d) {
  double best = 0.0;
  dvec2 landing(0.0);
  optics probe = o;
  probe.on_landing = [&](double weight, const dvec2& p) {
    if (weight > best) {
      best = weight;
      landing = p;
    }
  };
  probe.trace(origin, d, false, 0, 1.0);
  return landing;
}

// The landing point that a rendered radiance reveals: red and green over blue undo the pattern
// (with the internally reflected paths, a weighted mean of their landing points).
dvec2 revealed_landing(const vec3& radiance) {
  return {(radiance.x / radiance.z - 0.5) / slope, (radiance.y / radiance.z - 0.5) / slope};
}

constexpr int max_depth = 16;
constexpr double camera_z = 5.0;

// Camera rays that hit the ball: parallel to the axis at heights up to 0.6 R (incidence up to 37°),
// and oblique ones from a point camera, one of them through the centre.
struct camera_ray {
  const char* name;
  dvec3 origin, direction;
};
std::vector<camera_ray> camera_rays() {
  return {
      {"centre", {0, 0, camera_z}, {0, 0, -1}},
      {"paraxial 0.05 R", {0, 0.05, camera_z}, {0, 0, -1}},
      {"parallel 0.3 R", {0, 0.3, camera_z}, {0, 0, -1}},
      {"parallel 0.6 R diagonal", {0.36, -0.48, camera_z}, {0, 0, -1}},
      {"oblique", {0, 0, camera_z}, glm::normalize(dvec3(0.1, 0.25, -camera_z))},
      {"oblique through the centre", {1.5, 1.0, camera_z}, glm::normalize(dvec3(-1.5, -1.0, -camera_z))},
  };
}

TEST(ball_lens, radiance_through_the_ball_is_the_pattern_where_snell_and_fresnel_send_the_ray) {
  const double plane_z = -4.0;
  const scene s = ball_in_front_of_pattern(plane_z);
  const optics reference{plane_z, max_depth};
  for (const camera_ray& c : camera_rays()) {
    const vec3 seen = rendered(s, testing::make_ray(vec3(c.origin), vec3(c.direction)), max_depth);
    const dvec3 expected = reference.trace(c.origin, c.direction, false, 0, 1.0);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(seen[k], expected[k], 1e-6) << c.name << ", channel " << k;
    // The radiance points at the landing point of the main path, to within the internally
    // reflected share (under 1% of the weight).
    const dvec2 landing = main_landing(reference, c.origin, c.direction);
    const dvec2 revealed = revealed_landing(seen);
    EXPECT_NEAR(revealed.x, landing.x, 0.02 + 0.01 * glm::length(landing)) << c.name;
    EXPECT_NEAR(revealed.y, landing.y, 0.02 + 0.01 * glm::length(landing)) << c.name;
    const double error = std::max(
        {std::abs(seen.x - expected.x), std::abs(seen.y - expected.y), std::abs(seen.z - expected.z)});
    std::printf("%-28s landing (%8.4f, %8.4f), revealed (%8.4f, %8.4f), weight %.6f, largest error %.1e\n",
                c.name, landing.x, landing.y, revealed.x, revealed.y, seen.z, error);
  }
}

TEST(ball_lens, the_centre_ray_keeps_the_normal_incidence_fresnel_series) {
  // Straight through: (1 − F0)² with F0 = ((n − 1)/(n + 1))² = 0.04, plus the paths that bounce
  // between the back and front faces 2k times, (1 − F0)² F0^(2k): in all (1 − F0)/(1 + F0).
  const scene s = ball_in_front_of_pattern(-4.0);
  const vec3 seen = rendered(s, testing::make_ray(vec3(0, 0, camera_z), vec3(0, 0, -1)), max_depth);
  const double f0 = std::pow((glass_ior - 1.0) / (glass_ior + 1.0), 2.0);
  const double first = (1.0 - f0) * (1.0 - f0);
  const double series = (1.0 - f0) / (1.0 + f0);
  EXPECT_NEAR(first, 0.9216, 1e-12);
  EXPECT_NEAR(seen.z, series, 1e-5);
  EXPECT_NEAR(seen.x, series * pattern(0, 0).x, 1e-5);
  EXPECT_NEAR(seen.y, series * pattern(0, 0).y, 1e-5);
  // The bounced share (F0² (1 − F0)²/(1 − F0²) = 0.0015) is well above the tolerance.
  EXPECT_GT(seen.z - first, 1e-3);
  std::printf("centre weight %.6f; (1-F0)^2 = %.6f, (1-F0)/(1+F0) = %.6f\n", seen.z, first, series);
}

TEST(ball_lens, the_image_is_inverted_beyond_the_focus_and_upright_before_it) {
  // Paraxial ball-lens focus: f = nR / (2(n − 1)) = 1.5 R from the centre, 0.5 R behind the back
  // face. A ray above the axis crosses it at the focus: on a plane at z = −4 it lands below the
  // axis, on one at z = −1.2 (before the focus) still above it.
  const dvec3 origin(0.0, 0.05, camera_z), d(0, 0, -1);
  const double focus = glass_ior * ball_radius / (2.0 * (glass_ior - 1.0));
  ASSERT_NEAR(focus, 1.5, 1e-12);
  for (double plane_z : {-4.0, -1.2}) {
    const scene s = ball_in_front_of_pattern(plane_z);
    const dvec2 revealed = revealed_landing(rendered(s, testing::make_ray(vec3(origin), vec3(d)), max_depth));
    // Thin-lens estimate of the landing height: h (1 − distance / f).
    const double estimate = origin.y * (1.0 - (-plane_z) / focus);
    if (-plane_z > focus)
      EXPECT_LT(revealed.y, 0.0) << "plane at z " << plane_z;
    else
      EXPECT_GT(revealed.y, 0.0) << "plane at z " << plane_z;
    EXPECT_NEAR(revealed.y, estimate, 0.1 * std::abs(estimate)) << "plane at z " << plane_z;
    EXPECT_NEAR(revealed.x, 0.0, 1e-3) << "plane at z " << plane_z;
    std::printf("plane z %.1f: landing y %.5f, thin-lens estimate %.5f\n", plane_z, revealed.y, estimate);
  }
}

}  // namespace
}  // namespace kiln
