// Shadow probe for shading tests: a diffuse floor (material 0) under a point light, with whatever
// the caller placed over the half x > 0. Returns the per-channel ratio of the radiance of a floor
// point under that half to a mirror-image point outside it (same distance to the light), i.e. the
// light the cover lets through. Header-only; uses the Embree backend and Whitted shading.
#pragma once

#include "accel/embree/embree_accelerator.h"
#include "shade/whitted.h"
#include "support/test_scenes.h"

namespace kiln::testing {

inline vec3 light_through_cover(scene s) {
  add_box(s, vec3(-10, -10, -1), vec3(10, 10, 0), 0);
  light l;
  l.position = dvec3(0, 0, 4);
  l.intensity = 16.0f;
  s.lights.push_back(l);
  embree_accelerator accel(s);
  shading_options options;
  options.max_depth = 0;  // direct light only
  shading_context ctx{s, accel, options, scene_has_see_through(s)};
  ray_counts counts;
  vec3 open = trace_radiance(ctx, make_ray(vec3(-0.5f, 0, 0.5f), vec3(0, 0, -1)), path_state{}, counts);
  vec3 covered = trace_radiance(ctx, make_ray(vec3(0.5f, 0, 0.5f), vec3(0, 0, -1)), path_state{}, counts);
  return open.x > 0.0f && open.y > 0.0f && open.z > 0.0f ? covered / open : vec3(-1.0f);
}

}  // namespace kiln::testing
