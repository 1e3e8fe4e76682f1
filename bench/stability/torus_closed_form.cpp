#include "stability/torus_closed_form.h"

#include <cmath>

#include "geometry/polynomial.h"
#include "geometry/quadric.h"

namespace kiln::bench {

namespace {

// The largest real root of m³ + a·m² + b·m + c (Cardano, or the trigonometric form for three roots).
double largest_cubic_root(double a, double b, double c) {
  const double q = (a * a - 3.0 * b) / 9.0;
  const double r = (2.0 * a * a * a - 9.0 * a * b + 27.0 * c) / 54.0;
  if (r * r < q * q * q) {
    const double theta = std::acos(r / std::sqrt(q * q * q));
    return -2.0 * std::sqrt(q) * std::cos((theta - 2.0 * 3.14159265358979323846) / 3.0) - a / 3.0;
  }
  const double big_a = -std::copysign(std::cbrt(std::abs(r) + std::sqrt(r * r - q * q * q)), r);
  const double big_b = big_a != 0.0 ? q / big_a : 0.0;
  return big_a + big_b - a / 3.0;
}

}  // namespace

std::optional<double> intersect_torus_closed_form(double major_radius, double minor_radius, const dvec3& o,
                                                  const dvec3& d, double tmin, double tmax, bool polish) {
  const torus_ray_quartic quartic = make_torus_quartic(major_radius, minor_radius, o, d);
  const double* k = quartic.coefficients;
  // Depress s⁴ + a s³ + b s² + c s + e with s = y − a/4: y⁴ + p y² + q y + r.
  const double a = k[3], b = k[2], c = k[1], e = k[0];
  const double p = b - 3.0 * a * a / 8.0;
  const double q = c - a * b / 2.0 + a * a * a / 8.0;
  const double r = e - a * c / 4.0 + a * a * b / 16.0 - 3.0 * a * a * a * a / 256.0;
  // Ferrari's resolvent 8m³ + 8p m² + (2p² − 8r) m − q² = 0; any root m > 0 factors the quartic.
  const double m = largest_cubic_root(p, (p * p - 4.0 * r) / 4.0, -q * q / 8.0);
  double ys[4];
  int count = 0;
  if (m > 0.0) {
    const double w = std::sqrt(2.0 * m);
    for (double sign : {1.0, -1.0}) {
      // y² ∓ w·y + (p/2 + m ± q/(2w)) = 0
      polynomial_roots pair =
          solve_quadratic_half_b(1.0, -0.5 * sign * w, 0.5 * p + m + sign * q / (2.0 * w));
      for (int i = 0; i < pair.count; ++i) ys[count++] = pair.values[size_t(i)];
    }
  }
  std::optional<double> best;
  for (int i = 0; i < count; ++i) {
    double s = ys[i] - a / 4.0;
    if (polish)
      for (int step = 0; step < 2; ++step) {
        const double f = evaluate_polynomial(k, 4, s);
        const double df = ((4.0 * k[4] * s + 3.0 * k[3]) * s + 2.0 * k[2]) * s + k[1];
        if (df != 0.0) s -= f / df;
      }
    const double t = quartic.t_c + s / quartic.length;
    if (t > tmin && t < tmax && (!best || t < *best)) best = t;
  }
  return best;
}

}  // namespace kiln::bench
