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

// True when the hit lies within rounding of its triangle's boundary or of the ray's tmin/tmax.
bool hit_on_boundary(const scene& s, const ray& r, const hit& h);

// Classifies two closest-hit answers for ray r.
hit_verdict compare_hits(const scene& s, const ray& r, const std::optional<hit>& a,
                         const std::optional<hit>& b);

}  // namespace kiln
