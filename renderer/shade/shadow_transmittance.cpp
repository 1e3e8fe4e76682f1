#include "shade/shadow_transmittance.h"

#include "core/float_bits.h"
#include "shade/material_eval.h"
#include "shade/spawn_ray.h"

namespace kiln {

namespace {

// A shadow ray crossing more surfaces than this is treated as blocked: it
// bounds the work per shadow ray, and so much glass leaves little light anyway.
constexpr int max_shadow_crossings = 32;

// Whether surface_transmittance is 0 for every point of a surface with material m, whatever the
// point: then a shadow ray that meets it needs no surface point and no material evaluation.
bool passes_no_light(const material& m) { return !lets_light_through(m); }

}  // namespace

vec3 surface_transmittance(const scene& s, const surface_point& sp) {
  const material& m = s.materials[sp.material];
  const bool blend = m.alpha == alpha_mode::blend;
  if (passes_no_light(m)) return vec3(0.0f);
  material_point mp = evaluate_material(s, m, material_inputs_at(sp));
  vec3 through = mp.base_color * see_through_weight(mp);
  // BLEND: the uncovered share (1 - alpha) passes untouched, the covered share as above.
  if (blend) through = vec3(1.0f - mp.alpha) + mp.alpha * through;
  return through;
}

vec3 shadow_transmittance(const scene& s, const accelerator& accel, const ray& shadow, uint64_t& crossings) {
  vec3 transmittance(1.0f);
  // The segment still to walk: the caller's ray itself until a surface is crossed (taken by value,
  // it was copied whole from the fields its caller had just stored: a store-forwarding stall on
  // every shadow ray), then `rest`, moved past each crossing.
  const ray* segment = &shadow;
  ray rest;
  for (int i = 0; i < max_shadow_crossings; ++i) {
    std::optional<hit> h = accel.intersect_for_shadow(*segment);
    ++crossings;
    if (!h) return transmittance;
    const instance& blocker = s.instances[h->instance_id];
    const bool invisible = blocker.holdout == holdout_kind::invisible;  // casts no shadow: walk past it
    // An opaque blocker ends the walk: the same product surface_transmittance would give (times
    // 0), without reconstructing the surface point (a quadric's costs a projection onto it).
    if (!invisible && passes_no_light(s.materials[blocker.material])) return transmittance * vec3(0.0f);
    surface_point sp = make_surface_point(s, *h, *segment);
    if (!invisible) transmittance *= surface_transmittance(s, sp);
    if (transmittance == vec3(0.0f)) return transmittance;
    // Continue from just beyond the surface; the segment keeps its far end.
    if (segment != &rest) {
      rest = shadow;
      segment = &rest;
    }
    if (!continue_past(sp, rest)) return transmittance;
  }
  return vec3(0.0f);
}

}  // namespace kiln
