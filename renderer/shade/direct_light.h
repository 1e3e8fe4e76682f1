// Direct light at a shading point: every punctual light with its shadow ray, and the environment as a
// light, sampled both by its own importance and by the material's lobes and combined by multiple
// importance sampling (Veach's power heuristic), each sample with its shadow ray. With light groups
// and passes the light is filed by source and by lobe. Sees the Scene and the accelerator interface
// only, like the rest of shading.
//
// The light comes in three steps, so that the wave (render/tile_renderer.cpp) can answer the shadow
// rays of a run of camera hits together: plan_direct_light makes the point's terms (what each
// light or environment direction brings unshadowed) and their shadow rays, the rays are answered
// (one at a time, or all of a run at once through accelerator::occluded_batch), and
// resolve_direct_light sums the terms by their answers and files them. Every other shading point
// (direct_light) runs the same plan but answers and sums each term as it is made, keeping nothing;
// both sum in the same order, so they give the same bits.
#pragma once

#include <cstdint>
#include <vector>

#include "shade/whitted.h"

namespace kiln {

// The direct light leaving sp (material mp) toward to_viewer, for ray state s: s.planned's terms when
// the wave made them, else planned, answered and resolved here.
vec3 direct_light(const shading_context& ctx, const surface_point& sp, const material_point& mp,
                  const vec3& to_viewer, const path_state& s, ray_counts& counts);

// The share of the base's and the coat's glossy reflection the environment lights directly: what the
// perfect mirror (faded out with roughness, see shading_options) leaves, and none of the dielectric's
// transmissive share, whose reflection is traced.
glossy_weights environment_glossy_weights(const shading_options& options, const material_point& mp);

enum class light_term_kind : uint8_t {
  front,        // a punctual light on the side the surface faces
  back,         // a punctual light through a diffusely transmitting surface
  environment,  // one direction of the environment's samples
};

// One term of a shading point's direct light, before its shadow ray is answered.
struct light_term {
  light_term_kind kind = light_term_kind::front;
  bool shadowed = false;  // it has a shadow ray: the next of its point's rays, in order
  uint32_t light = 0;     // front and back: the punctual light's index
  vec3 value{0.0f};       // front and back: the light it brings unshadowed (f · E · cos θ)
  brdf_lobes lobes;       // front, with passes: f by lobe; environment: f by lobe
  vec3 incident{0.0f};    // front: E · cos θ; environment: the map's radiance · cos θ · MIS weight
};

// The terms of one or many shading points, their shadow rays and, once answered, the rays'
// visibility (0 to 1 by channel). Kept and cleared, not freed, from one run to the next.
struct light_terms {
  std::vector<light_term> terms;
  std::vector<ray> rays;
  std::vector<vec3> visibility;
  // Scratch of answer_shadow_rays_together: occluded_batch's answers, and the rays (and their
  // indices in rays) still open after a step.
  std::vector<uint8_t> blocked;
  std::vector<ray> open_rays;
  std::vector<uint32_t> open_index;
  void clear() {
    terms.clear();
    rays.clear();
    visibility.clear();
  }
};

// Where one shading point's terms and rays lie in a light_terms.
struct light_terms_span {
  uint32_t first_term = 0, term_count = 0;
  uint32_t first_ray = 0;
  int environment_pairs = 0;  // the environment's sample pairs taken (0: it lights nothing)
};

// A point's planned direct light: the wave's camera hits carry one in path_state::planned.
struct planned_light {
  const light_terms* terms = nullptr;
  light_terms_span span;
};

// What of a ray's state the direct light reads.
struct light_query {
  ray_cone cone;          // the ray's cone at the point (the highlight's footprint)
  uint32_t seed = 0;      // the ray's random numbers
  pixel_stratum stratum;  // the camera's first surface: its sample's place in the pixel
  bool camera = false;    // on the camera's path (the environment takes all its samples)
  bool passes = false;    // the light by lobe is wanted (path_record's passes)
};
light_query light_query_of(const path_state& s);

// Appends sp's terms and shadow rays to out.
light_terms_span plan_direct_light(const shading_context& ctx, const surface_point& sp,
                                   const material_point& mp, const vec3& to_viewer, const light_query& q,
                                   light_terms& out);

// Answers all of t's rays together through occlusion batches (Embree's packets; one at a time
// without ctx.shadow_packets). In scenes with
// see-through surfaces in steps: a batch that sees only what stops light (blocked: 0), then one of
// the rest that sees only see-through surfaces (clear: 1), then the transmittance walk of the rays
// that cross one, past see-through surfaces alone.
void answer_shadow_rays_together(const shading_context& ctx, light_terms& t, ray_counts& counts);

// The direct light of the point whose terms span holds (answered), filed into s.record.
vec3 resolve_direct_light(const shading_context& ctx, const light_terms& t, const light_terms_span& span,
                          const path_state& s);

}  // namespace kiln
