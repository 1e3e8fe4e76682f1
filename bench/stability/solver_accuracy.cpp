#include "stability/solver_accuracy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "geometry/quadric.h"
#include "stability/torus_accuracy.h"

namespace kiln::bench {

namespace {

// Each draw in its own statement: the order of evaluation of function arguments is unspecified.
dvec3 random_cube_point(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double x = u(rng), y = u(rng);
  return dvec3(x, y, u(rng));
}

dvec3 random_unit(std::mt19937_64& rng) {
  for (;;) {
    const dvec3 v = random_cube_point(rng);
    const double l = glm::length(v);
    if (l > 0.1 && l <= 1.0) return v / l;
  }
}

struct test_ray {
  dvec3 o, d;
  std::optional<double> reference;
};

// The nearer positive root of t² + b·t + c = 0 in precision T, by either formula.
template <typename T>
std::optional<double> unit_sphere_roots(const dvec3& o_in, const dvec3& d_in, bool stable) {
  const T ox = T(o_in.x), oy = T(o_in.y), oz = T(o_in.z), dx = T(d_in.x), dy = T(d_in.y), dz = T(d_in.z);
  const T b = 2 * (ox * dx + oy * dy + oz * dz);
  const T c = ox * ox + oy * oy + oz * oz - 1;
  const T disc = b * b - 4 * c;
  if (!(disc >= 0)) return std::nullopt;
  const T root = std::sqrt(disc);
  T t0, t1;
  if (stable) {
    const T q = -(b + std::copysign(root, b)) / 2;
    t0 = q;
    t1 = q != 0 ? c / q : q;
    if (t0 > t1) std::swap(t0, t1);
  } else {
    t0 = (-b - root) / 2;
    t1 = (-b + root) / 2;
  }
  if (t0 > 0) return double(t0);
  if (t1 > 0) return double(t1);
  return std::nullopt;
}

// Reference: the closest-approach form in long double (64-bit significand), without assuming
// |d| = 1 (a float-rounded direction is off by ~1e-16, which matters at 1e7).
std::optional<double> sphere_reference(const dvec3& o, const dvec3& d) {
  const long double ox = o.x, oy = o.y, oz = o.z, dx = d.x, dy = d.y, dz = d.z;
  const long double dd = dx * dx + dy * dy + dz * dz;
  const long double tc = -(ox * dx + oy * dy + oz * dz) / dd;
  const long double px = ox + tc * dx, py = oy + tc * dy, pz = oz + tc * dz;
  const long double h2 = 1.0L - (px * px + py * py + pz * pz);
  if (h2 < 0.0L) return std::nullopt;
  return double(tc - std::sqrt(h2 / dd));
}

// Distance of o + t·d from the unit sphere, in long double.
double sphere_distance(const dvec3& o, const dvec3& d, double t) {
  const long double x = o.x + (long double)t * d.x, y = o.y + (long double)t * d.y,
                    z = o.z + (long double)t * d.z;
  return double(std::abs(std::sqrt(x * x + y * y + z * z) - 1.0L));
}

// Distance of o + t·d from the torus (major 1, minor 0.3) to first order, |F| / |∇F|, in long double.
double torus_distance(const dvec3& o, const dvec3& d, double t) {
  const long double x = o.x + (long double)t * d.x, y = o.y + (long double)t * d.y,
                    z = o.z + (long double)t * d.z;
  const long double k = x * x + y * y + z * z + 1.0L - 0.09L;
  const long double f = k * k - 4.0L * (x * x + y * y);
  const long double gx = 4.0L * k * x - 8.0L * x, gy = 4.0L * k * y - 8.0L * y, gz = 4.0L * k * z;
  const long double g = std::sqrt(gx * gx + gy * gy + gz * gz);
  return g > 0.0L ? double(std::abs(f) / g) : double(std::abs(f));
}

// Scores one solver on prepared rays; `solve` is timed over `repeats` passes. The error of a hit is
// its distance from the surface (`distance`, in units of the shape's size): t itself is
// ill-conditioned near silhouettes, where a tiny move along the surface changes t a lot.
// A hit more than t_tolerance from the reference's t is a different root (torus), however close to
// the surface it lies.
template <typename Solve, typename Distance>
solver_accuracy score(const std::vector<test_ray>& rays, int repeats, double t_tolerance, Solve solve,
                      Distance distance) {
  solver_accuracy out;
  for (const test_ray& r : rays) {
    ++out.rays;
    std::optional<double> got = solve(r.o, r.d);
    if (got && !std::isfinite(*got)) got.reset();
    if (r.reference) ++out.reference_hits;
    if (r.reference && !got) {
      ++out.missed;
    } else if (!r.reference && got) {
      ++out.invented;
    } else if (r.reference && got) {
      const double error = distance(r.o, r.d, *got);
      out.max_error = std::max(out.max_error, error);
      if (error > wrong_hit_tolerance || std::abs(*got - *r.reference) > t_tolerance) ++out.wrong;
    }
  }
  // The fastest of `repeats` timed passes: the machine is shared, and a pass can be preempted.
  double sink = 0.0, best_ns = inf;
  for (int k = 0; k < repeats; ++k) {
    const auto start = std::chrono::steady_clock::now();
    for (const test_ray& r : rays) sink += solve(r.o, r.d).value_or(0.0);
    best_ns = std::min(
        best_ns, std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count());
  }
  out.ns_per_ray = rays.empty() ? 0.0 : best_ns / double(rays.size());
  // Keeps the timed calls from being optimised away.
  if (sink == 42.0) out.ns_per_ray += 1e-300;
  return out;
}

}  // namespace

const char* solver_name(sphere_solver s) {
  switch (s) {
    case sphere_solver::naive_float:
      return "naive_float";
    case sphere_solver::naive_double:
      return "naive_double";
    case sphere_solver::stable_float:
      return "stable_float";
    case sphere_solver::stable_double:
      return "stable_double";
    case sphere_solver::kiln:
      break;
  }
  return "kiln";
}

const char* solver_name(torus_solver s) {
  switch (s) {
    case torus_solver::closed_form:
      return "closed_form";
    case torus_solver::closed_form_newton:
      return "closed_form_newton";
    case torus_solver::kiln:
      break;
  }
  return "kiln";
}

std::optional<double> solve_unit_sphere(sphere_solver s, const dvec3& o, const dvec3& d) {
  switch (s) {
    case sphere_solver::naive_float:
      return unit_sphere_roots<float>(o, d, false);
    case sphere_solver::naive_double:
      return unit_sphere_roots<double>(o, d, false);
    case sphere_solver::stable_float:
      return unit_sphere_roots<float>(o, d, true);
    case sphere_solver::stable_double:
      return unit_sphere_roots<double>(o, d, true);
    case sphere_solver::kiln:
      break;
  }
  quadric sphere;
  sphere.kind = quadric_kind::sphere;
  sphere.radius = 1.0;
  sphere.bounds = bounds3{dvec3(-1.0), dvec3(1.0)};
  const std::optional<quadric_ray_hit> h = intersect_quadric(sphere, o, d, 0.0, 1e30);
  if (!h) return std::nullopt;
  return h->t;
}

solver_accuracy measure_sphere_solver(sphere_solver s, double distance, int rays, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<test_ray> prepared;
  for (int i = 0; i < rays; ++i) {
    // Origins and directions are float-representable, as rays in the renderer are.
    const dvec3 o = dvec3(vec3(random_unit(rng) * distance));
    const dvec3 target = 0.7 * random_cube_point(rng);
    const dvec3 d = glm::normalize(dvec3(vec3(glm::normalize(target - o))));
    prepared.push_back({o, d, {}});
    // From the stored ray: exactly the doubles every solver sees.
    prepared.back().reference = sphere_reference(prepared.back().o, prepared.back().d);
  }
  return score(
      prepared, 5, inf, [s](const dvec3& o, const dvec3& d) { return solve_unit_sphere(s, o, d); },
      sphere_distance);
}

std::array<solver_accuracy, 3> measure_torus_solvers(double distance, bool grazing, int rays, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<test_ray> prepared;
  for (int i = 0; i < rays; ++i) {
    const torus_test_ray r = make_torus_test_ray(rng, distance, grazing);
    prepared.push_back({r.origin, r.direction, torus_reference_hit(r.origin, r.direction)});
  }
  std::array<solver_accuracy, 3> out;
  for (int k = 0; k < 3; ++k)
    out[size_t(k)] = score(
        prepared, 3, 1e-3, [k](const dvec3& o, const dvec3& d) { return solve_torus(k, o, d); },
        torus_distance);
  return out;
}

}  // namespace kiln::bench
