#include "shade/shadow_transmittance.h"

#include "core/float_bits.h"
#include "shade/material_eval.h"

namespace kiln {

namespace {

// A shadow ray crossing more surfaces than this is treated as blocked: it
// bounds the work per shadow ray, and so much glass leaves little light anyway.
constexpr int max_shadow_crossings = 32;

}  // namespace

vec3 surface_transmittance(const scene& s, const surface_point& sp) {
  const material& m = s.materials[sp.material];
  const bool blend = m.alpha == alpha_mode::blend;
  if (m.transmission_factor <= 0.0f && !blend) return vec3(0.0f);
  material_point mp = evaluate_material(s, m, material_inputs_at(sp));
  vec3 through = mp.base_color * see_through_weight(mp);
  // BLEND: the uncovered share (1 - alpha) passes untouched, the covered share as above.
  if (blend) through = vec3(1.0f - mp.alpha) + mp.alpha * through;
  return through;
}

vec3 shadow_transmittance(const scene& s, const accelerator& accel, ray r, uint64_t& crossings) {
  vec3 transmittance(1.0f);
  for (int i = 0; i < max_shadow_crossings; ++i) {
    std::optional<hit> h = accel.intersect(r);
    ++crossings;
    if (!h) return transmittance;
    surface_point sp = make_surface_point(s, *h, r);
    transmittance *= surface_transmittance(s, sp);
    if (transmittance == vec3(0.0f)) return transmittance;
    // Continue from just beyond the surface; the segment keeps its far end.
    vec3 origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, r.direction);
    if (!std::isinf(r.tmax)) {
      r.tmax -= glm::length(origin - r.origin);
      if (r.tmax <= 0.0f) return transmittance;
    }
    r.origin = origin;
  }
  return vec3(0.0f);
}

}  // namespace kiln
