// Deciding whether two backends' answers for one ray agree. Two correct backends may differ
// within the rounding error of the hit (Embree and the grid transform rays and solve for t with
// different float formulas), and may pick different primitives where two surfaces meet the ray at
// the same t (a genuine tie) or where the ray grazes a shared edge. Those are reported apart from
// real mismatches. Depends on scene and geometry only.
#pragma once

#include <optional>

#include "core/ray.h"
#include "scene/scene.h"

namespace kiln {

enum class hit_verdict {
  agree,     // both miss, or the same primitive at t within the error bound
  tie,       // different primitives at the same t within the error bound
  edge,      // one backend hits within rounding of a triangle edge or of the segment's end; the other misses
  mismatch,  // anything else: a real disagreement
};

// Bound on how far a correct backend's t may stray for this hit: the hit point's rounding error
// plus the float error of moving the ray into object space, divided by the cosine between the ray
// and the surface (a grazing ray turns a small offset into a long stretch of t).
float hit_t_tolerance(const scene& s, const ray& r, const hit& h);

// True when a triangle hit lies at a t the watertight test (the grid's) refuses as within its own
// rounding error of the origin: Embree has no such rejection and reports the hit, the grid goes
// on to the next surface. Seen on BrainStem's Draco variant: a ray starting 2e-4 from a sliver
// (edges 0.48, 0.48, 0.008; double precision puts the hit at t = 1.989e-4, barycentrics 0.27,
// 0.60, 0.13) whose bound is wider than that t.
bool within_watertight_t_bound(const scene& s, const ray& r, const hit& h);

// True when the hit lies within rounding of its triangle's boundary or of the ray's tmin/tmax
// (including within_watertight_t_bound).
bool hit_on_boundary(const scene& s, const ray& r, const hit& h);

// Classifies two closest-hit answers for ray r.
hit_verdict compare_hits(const scene& s, const ray& r, const std::optional<hit>& a,
                         const std::optional<hit>& b);

}  // namespace kiln
