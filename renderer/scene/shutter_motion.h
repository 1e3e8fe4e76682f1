// Where a moving scene is at a time within the shutter (a ray's time, 0 at its opening and 1 at
// its closing): instance transforms and deformed vertices interpolated linearly between the two
// steps around that time, the rule Embree's motion blur applies, so that shading rebuilds the
// surface Embree intersected. Depends on scene only.
#pragma once

#include <array>
#include <cstdint>

#include "scene/scene.h"

namespace kiln {

// The interval of a time among `steps` evenly spaced steps: between step and step + 1, at
// fraction in [0, 1] (Embree's own split of ray time, kernels/common/ray.h).
struct shutter_interval {
  uint32_t step = 0;
  float fraction = 0.0f;
};
shutter_interval interval_at(uint32_t steps, float time);

// Inline: every hit record and shading point asks, and almost every scene is still.
inline bool instance_moves(const scene& s, uint32_t instance) {
  return s.shutter.any() && instance < s.shutter.instance_steps.size() &&
         !s.shutter.instance_steps[instance].empty();
}
inline bool mesh_deforms(const scene& s, uint32_t mesh) {
  return s.shutter.any() && mesh < s.shutter.mesh_positions.size() && !s.shutter.mesh_positions[mesh].empty();
}

// s.instances[i] as it sits at `time`: world_from_object interpolated in float (as Embree does),
// with its inverse and normal matrix. The instance itself when it does not move.
instance instance_at(const scene& s, uint32_t i, float time);

// The three corners of triangle idx of a deforming mesh at `time` (positions, then normals when
// the mesh has them), interpolated in float as Embree interpolates its vertex buffers.
std::array<vec3, 3> triangle_positions_at(const scene& s, uint32_t mesh, const uint32_t* idx, float time);
std::array<vec3, 3> triangle_normals_at(const scene& s, uint32_t mesh, const uint32_t* idx, float time);

}  // namespace kiln
