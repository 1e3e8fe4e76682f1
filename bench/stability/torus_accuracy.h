// Torus solver accuracy against a brute-force long-double reference (for quadric_bench).
#pragma once

#include <cstdint>
#include <optional>
#include <random>

#include "core/math.h"

namespace kiln::bench {

struct torus_accuracy {
  int64_t rays = 0;
  int64_t reference_hits = 0;
  int64_t missed = 0;    // the reference hits, the solver does not
  int64_t invented = 0;  // the solver hits, the reference does not
  int64_t wrong_t = 0;   // both hit, |t − t_ref| > 1e-6·(1 + t_ref)
};

// Rays from `distance` away; grazing = aimed along the tangent plane of a random surface point
// with a normal component of 1e-4 to 1e-3 (the hard case for quartic solvers).
// solver: 0 kiln's root isolation, 1 closed form (Ferrari), 2 closed form + Newton polishing.
torus_accuracy measure_torus_accuracy(int64_t rays, double distance, bool grazing, uint64_t seed,
                                      int solver = 0);

// A test ray of measure_torus_accuracy: unit direction, origin `distance` before its target.
struct torus_test_ray {
  dvec3 origin{0.0};
  dvec3 direction{0.0};
};
torus_test_ray make_torus_test_ray(std::mt19937_64& rng, double distance, bool grazing);

// The first hit (t > 0) of the torus (major 1, minor 0.3) by dense sign sampling of the quartic in
// long double and bisection: slow (2·10⁵ evaluations per ray), but it skips no root whose chord is
// longer than the sampling step.
std::optional<double> torus_reference_hit(const dvec3& o, const dvec3& d);

// One torus solve (major 1, minor 0.3) with the chosen solver.
std::optional<double> solve_torus(int solver, const dvec3& o, const dvec3& d);

}  // namespace kiln::bench
