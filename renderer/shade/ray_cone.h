// Ray cones (Akenine-Möller et al., "Texture Level of Detail Strategies for Real-Time Ray Tracing",
// Ray Tracing Gems, chapter 20): a pixel's footprint carried beside a ray through the Whitted
// recursion so that texture lookups can pick a mip level. Kept out of core/ray.h: accelerators
// never need it. Depends on core/math only.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace kiln {

// A cone of width `width` at the ray's origin opening by `spread` radians (full angle, small-angle
// approximation: width grows by spread·distance). Width 0 and spread 0 mean no footprint: texture
// lookups then read level 0, as before ray cones existed.
struct ray_cone {
  float width = 0.0f;
  float spread = 0.0f;

  bool empty() const { return width <= 0.0f && spread <= 0.0f; }
};

// The cone after travelling `distance` along its ray.
inline ray_cone cone_at(const ray_cone& c, float distance) {
  return {c.width + c.spread * distance, c.spread};
}

// The cone leaving a planar mirror: width and spread continue unchanged, so the footprint behind the
// mirror equals that of the unfolded straight ray (no curvature term: normals of curved surfaces
// would widen it, which Whitted's sharp mirror images do not need for level selection).
inline ray_cone reflected_cone(const ray_cone& at_hit) { return at_hit; }

// The cone leaving a refracting interface: by Snell's law n_i sin θ_i = n_t sin θ_t, a small
// angular spread dθ_i becomes dθ_t = eta·cos θ_i / cos θ_t · dθ_i (eta = n_i / n_t). The cosines are
// taken against the normal, clamped away from grazing so that the spread stays finite.
inline ray_cone refracted_cone(const ray_cone& at_hit, float eta, float cos_incident, float cos_transmitted) {
  const float ci = std::max(std::abs(cos_incident), 1e-3f);
  const float ct = std::max(std::abs(cos_transmitted), 1e-3f);
  return {at_hit.width, at_hit.spread * eta * ci / ct};
}

}  // namespace kiln
