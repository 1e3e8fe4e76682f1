// One camera sample: the ray through a film position, shaded, with what the AOVs and adaptive
// refinement need. A pure function of the position, so recomputing a sample gives the same bytes.
// Depends on shade and render; never on a backend.
#pragma once

#include "render/view_camera.h"
#include "shade/ray_cone.h"
#include "shade/whitted.h"

#include <cstdint>

namespace kiln {

constexpr uint32_t no_instance = 0xFFFFFFFFu;  // the instance id of a sample that hit nothing

struct camera_sample {
  vec4 rgba{0.0f};    // premultiplied: (radiance, 1) on a hit or a visible background, 0 otherwise
  float depth = inf;  // ray distance of the hit; +inf on a miss
  vec3 normal{0.0f};  // world shading normal of the hit; 0 on a miss
  uint32_t instance = no_instance;
  bool finite = true;  // false: the radiance was NaN or infinite; rgba is then 0 and it is counted
};

// Traces and shades the camera ray through film position (px, py) in pixels (row 0 at the top).
// A miss sees the environment with alpha 1 when show_background is set, else it is transparent.
// cone is the ray's footprint at the camera (for texture filtering along the whole path).
camera_sample trace_camera_sample(const shading_context& ctx, const view_camera& cam, bool show_background,
                                  double px, double py, const ray_cone& cone, ray_counts& counts);

}  // namespace kiln
