#include "stability/torus_accuracy.h"

#include <cmath>
#include <random>

#include "geometry/quadric.h"
#include "stability/torus_closed_form.h"

namespace kiln::bench {

namespace {

constexpr double major = 1.0, minor = 0.3;

long double torus_f(long double x, long double y, long double z) {
  const long double s = x * x + y * y + z * z + major * major - minor * minor;
  return s * s - 4.0L * major * major * (x * x + y * y);
}

}  // namespace

// Dense sign sampling of the quartic in long double inside the torus' box, then bisection.
std::optional<double> torus_reference_hit(const dvec3& o, const dvec3& d) {
  double t0 = 0.0, t1 = 1e30;
  const double outer = major + minor;
  if (!clip_ray_to_box({dvec3(-outer, -outer, -minor), dvec3(outer, outer, minor)}, o, d, t0, t1)) return {};
  const int steps = 200000;
  auto f = [&](long double t) { return torus_f(o.x + t * d.x, o.y + t * d.y, o.z + t * d.z); };
  long double prev = f(t0);
  for (int i = 1; i <= steps; ++i) {
    const long double t = t0 + (t1 - t0) * (long double)i / steps;
    const long double v = f(t);
    if ((v < 0) != (prev < 0)) {
      long double lo = t0 + (t1 - t0) * (long double)(i - 1) / steps, hi = t, f_lo = prev;
      for (int k = 0; k < 100; ++k) {
        const long double mid = 0.5L * (lo + hi), fm = f(mid);
        if ((fm < 0) == (f_lo < 0))
          lo = mid, f_lo = fm;
        else
          hi = mid;
      }
      return double(0.5L * (lo + hi));
    }
    prev = v;
  }
  return {};
}

std::optional<double> solve_torus(int solver, const dvec3& o, const dvec3& d) {
  if (solver == 0) return intersect_torus(major, minor, o, d, 0.0, 1e30);
  return intersect_torus_closed_form(major, minor, o, d, 0.0, 1e30, solver == 2);
}

torus_test_ray make_torus_test_ray(std::mt19937_64& rng, double distance, bool grazing) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  quadric q;
  q.kind = quadric_kind::torus;
  q.major_radius = major;
  q.radius = minor;
  dvec3 d;
  dvec3 target;
  if (grazing) {
    // A surface point, and a direction in its tangent plane tilted by less than 1e-3.
    const double phi = 3.14159265 * u(rng), theta = 3.14159265 * u(rng);
    target = dvec3((major + minor * std::cos(theta)) * std::cos(phi),
                   (major + minor * std::cos(theta)) * std::sin(phi), minor * std::sin(theta));
    const dvec3 n = glm::normalize(quadric_gradient(q, target));
    dvec3 t = glm::normalize(glm::cross(n, dvec3(u(rng), u(rng), u(rng))));
    // Tilts of 1e-4..1e-3 keep every chord longer than the reference's sampling step.
    const double tilt = std::copysign(1e-4 + 9e-4 * std::abs(u(rng)), u(rng));
    d = glm::normalize(t + tilt * n);
  } else {
    target = dvec3(1.3 * u(rng), 1.3 * u(rng), 0.3 * u(rng));
    d = glm::normalize(dvec3(u(rng), u(rng), u(rng)));
  }
  return {target - distance * d, d};
}

torus_accuracy measure_torus_accuracy(int64_t rays, double distance, bool grazing, uint64_t seed,
                                      int solver) {
  std::mt19937_64 rng(seed);
  torus_accuracy out;
  for (int64_t i = 0; i < rays; ++i) {
    const torus_test_ray r = make_torus_test_ray(rng, distance, grazing);
    const dvec3 o = r.origin, d = r.direction;
    ++out.rays;
    const std::optional<double> ref = torus_reference_hit(o, d);
    const std::optional<double> got = solve_torus(solver, o, d);
    if (ref) ++out.reference_hits;
    if (ref && !got)
      ++out.missed;
    else if (!ref && got)
      ++out.invented;
    else if (ref && got && std::abs(*got - *ref) > 1e-6 * (1.0 + *ref))
      ++out.wrong_t;
  }
  return out;
}

}  // namespace kiln::bench
