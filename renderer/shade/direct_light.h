// Direct light at a shading point: every punctual light with its shadow ray, and the environment as a
// light, sampled both by its own importance and by the material's lobes and combined by multiple
// importance sampling (Veach's power heuristic), each sample with its shadow ray. With light groups
// and passes the light is filed by source and by lobe. Sees the Scene and the accelerator interface
// only, like the rest of shading.
#pragma once

#include "shade/whitted.h"

namespace kiln {

// The direct light leaving sp (material mp) toward to_viewer, for ray state s.
vec3 direct_light(const shading_context& ctx, const surface_point& sp, const material_point& mp,
                  const vec3& to_viewer, const path_state& s, ray_counts& counts);

// The share of the base's and the coat's glossy reflection the environment lights directly: what the
// perfect mirror (faded out with roughness, see shading_options) leaves, and none of the dielectric's
// transmissive share, whose reflection is traced.
glossy_weights environment_glossy_weights(const shading_options& options, const material_point& mp);

}  // namespace kiln
