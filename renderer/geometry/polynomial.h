// Real roots of low-degree polynomials in double precision, for the analytic primitives.
// The quadratic uses the stable form (no cancellation between -b and the root of the
// discriminant); degrees 3 and 4 isolate roots between the roots of the derivative, so a root
// is never skipped unless the polynomial only touches zero (a tangent ray). Depends on nothing.
#pragma once

#include <array>
#include <cstddef>

namespace kiln {

// Up to four real roots, ascending.
struct polynomial_roots {
  std::array<double, 4> values{};
  int count = 0;
  void add(double r) { values[size_t(count++)] = r; }
};

// Roots of a·t² + 2·h·t + c = 0 (half-b form): q = -(h + sign(h)·√(h²-ac)), t = q/a and c/q.
// a = 0 degrades to the linear root. Roots are returned ascending; a negative discriminant gives none.
polynomial_roots solve_quadratic_half_b(double a, double h, double c);

// Real roots in [lo, hi] of Σ coefficients[i]·tⁱ, degree ≤ 4 (coefficients[0] is the constant).
// Each root is bracketed between consecutive critical points and refined by safeguarded Newton
// iteration to full double precision.
polynomial_roots polynomial_roots_in(const double* coefficients, int degree, double lo, double hi);

// Σ coefficients[i]·tⁱ by Horner's rule.
double evaluate_polynomial(const double* coefficients, int degree, double t);

}  // namespace kiln
