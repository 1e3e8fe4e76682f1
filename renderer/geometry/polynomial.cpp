#include "geometry/polynomial.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kiln {

polynomial_roots solve_quadratic_half_b(double a, double h, double c) {
  polynomial_roots out;
  const double discriminant = h * h - a * c;
  if (discriminant < 0.0) return out;
  // q has the sign of -h, so h and the root never cancel (Numerical Recipes 5.6; RTG ch. 7).
  const double q = -(h + std::copysign(std::sqrt(discriminant), h));
  if (a != 0.0) out.add(q / a);
  if (q != 0.0) out.add(c / q);
  if (out.count == 2 && out.values[0] > out.values[1]) std::swap(out.values[0], out.values[1]);
  return out;
}

double evaluate_polynomial(const double* coefficients, int degree, double t) {
  double value = coefficients[degree];
  for (int i = degree - 1; i >= 0; --i) value = value * t + coefficients[i];
  return value;
}

namespace {

// The root of p in [lo, hi] where p(lo) and p(hi) have opposite signs: Newton steps that stay
// inside the shrinking bracket, bisection otherwise (Numerical Recipes' rtsafe).
double refine_bracketed_root(const double* p, const double* dp, int degree, double lo, double hi,
                             double f_lo) {
  double t = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double f = evaluate_polynomial(p, degree, t);
    if (f == 0.0) return t;
    if ((f < 0.0) == (f_lo < 0.0))
      lo = t;
    else
      hi = t;
    const double slope = evaluate_polynomial(dp, degree - 1, t);
    double next = slope != 0.0 ? t - f / slope : lo - 1.0;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    // Converged when the step no longer changes t in double precision.
    if (next == t ||
        hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(lo), std::abs(hi)))
      return next;
    t = next;
  }
  return t;
}

}  // namespace

polynomial_roots polynomial_roots_in(const double* coefficients, int degree, double lo, double hi) {
  polynomial_roots out;
  // Trailing zero leading coefficients lower the degree (e.g. a ray parallel to an axis).
  while (degree > 0 && coefficients[degree] == 0.0) --degree;
  if (degree <= 0 || !(lo <= hi)) return out;
  if (degree == 1) {
    const double t = -coefficients[0] / coefficients[1];
    if (t >= lo && t <= hi) out.add(t);
    return out;
  }
  if (degree == 2) {
    polynomial_roots all = solve_quadratic_half_b(coefficients[2], 0.5 * coefficients[1], coefficients[0]);
    for (int i = 0; i < all.count; ++i)
      if (all.values[size_t(i)] >= lo && all.values[size_t(i)] <= hi) out.add(all.values[size_t(i)]);
    return out;
  }
  // Between two consecutive critical points p is monotonic: at most one root, found by bracketing.
  double derivative[4];
  for (int i = 1; i <= degree; ++i) derivative[i - 1] = coefficients[i] * double(i);
  polynomial_roots critical = polynomial_roots_in(derivative, degree - 1, lo, hi);
  double ends[6];
  int end_count = 0;
  ends[end_count++] = lo;
  for (int i = 0; i < critical.count; ++i) ends[end_count++] = critical.values[size_t(i)];
  ends[end_count++] = hi;
  double f_prev = evaluate_polynomial(coefficients, degree, ends[0]);
  if (f_prev == 0.0) out.add(ends[0]);
  for (int i = 1; i < end_count; ++i) {
    const double f = evaluate_polynomial(coefficients, degree, ends[i]);
    if (f == 0.0) {
      if (out.count == 0 || out.values[size_t(out.count - 1)] != ends[i]) out.add(ends[i]);
    } else if (f_prev != 0.0 && (f < 0.0) != (f_prev < 0.0)) {
      out.add(refine_bracketed_root(coefficients, derivative, degree, ends[i - 1], ends[i], f_prev));
    }
    f_prev = f;
    if (out.count == 4) break;
  }
  return out;
}

}  // namespace kiln
