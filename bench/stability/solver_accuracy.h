// Ray-solver accuracy against long-double references: the sphere by the textbook and the stable
// quadratic in float and double against kiln's intersect_quadric, and the torus by kiln's
// root-isolating solver against the closed form (with and without Newton polishing). Shared by
// bench/stability_study (CSV for chart 5) and tests/stability. Depends on geometry only.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "core/math.h"

namespace kiln::bench {

enum class sphere_solver { naive_float, naive_double, stable_float, stable_double, kiln };
const char* solver_name(sphere_solver s);

// The nearer root t > 0 of |o + t·d|² = 1 (unit d) with the chosen formula: naive is
// (−b − √(b² − 4c))/2; stable is q = −(b + sign(b)·√(b² − 4c))/2, roots q and c/q (Numerical
// Recipes); kiln is intersect_quadric (closest-approach form in double, docs/quadrics.md).
std::optional<double> solve_unit_sphere(sphere_solver s, const dvec3& o, const dvec3& d);

enum class torus_solver { kiln = 0, closed_form = 1, closed_form_newton = 2 };
const char* solver_name(torus_solver s);

// A hit is wrong when it lies off the surface by more than this fraction of the shape's size
// (the sphere's radius, the torus' major radius): visible once the shape covers 10⁴ pixels.
constexpr double wrong_hit_tolerance = 1e-4;

struct solver_accuracy {
  int64_t rays = 0;
  int64_t reference_hits = 0;
  int64_t missed = 0;    // the reference hits, the solver does not (or returns a non-finite t)
  int64_t invented = 0;  // the solver hits, the reference does not
  // Both hit, but o + t·d is off the surface by > wrong_hit_tolerance·size, or (torus) t is a
  // different root than the reference's (off by more than 1e-3).
  int64_t wrong = 0;
  double max_error = 0.0;  // max distance of o + t·d from the surface / size, over rays both hit
  double ns_per_ray = 0.0;
  double miss_rate() const { return reference_hits ? double(missed) / double(reference_hits) : 0.0; }
  // Every way a pixel can come out wrong, per ray.
  double failure_rate() const { return rays ? double(missed + invented + wrong) / double(rays) : 0.0; }
};

// `rays` rays from `distance` away toward points inside 0.7 of the unit sphere, origins and
// directions rounded to float as the renderer's rays are.
solver_accuracy measure_sphere_solver(sphere_solver s, double distance, int rays, uint64_t seed);

// Rays of make_torus_test_ray (grazing: tilted 1e-4..1e-3 off a tangent plane) against the
// brute-force torus reference (slow: ~1 ms per ray, computed once for all three solvers), indexed
// by torus_solver.
std::array<solver_accuracy, 3> measure_torus_solvers(double distance, bool grazing, int rays, uint64_t seed);

}  // namespace kiln::bench
