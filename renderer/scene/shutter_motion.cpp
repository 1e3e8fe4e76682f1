#include "scene/shutter_motion.h"

#include <algorithm>
#include <cmath>

namespace kiln {

shutter_interval interval_at(uint32_t steps, float time) {
  if (steps < 2) return {};
  const float scaled = std::clamp(time, 0.0f, 1.0f) * float(steps - 1);
  const uint32_t step = std::min(uint32_t(std::floor(scaled)), steps - 2);
  return {step, scaled - float(step)};
}

instance instance_at(const scene& s, uint32_t i, float time) {
  instance moved = s.instances[i];
  if (!instance_moves(s, i)) return moved;
  const std::vector<dmat4>& steps = s.shutter.instance_steps[i];
  const shutter_interval at = interval_at(s.shutter.steps, time);
  // Embree interpolates the float matrices it was given; so does this, then widens to double.
  const float f = at.fraction;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) {
      const float a = float(steps[at.step][c][r]), b = float(steps[at.step + 1][c][r]);
      moved.world_from_object[c][r] = double((1.0f - f) * a + f * b);
    }
  finish_instance_transform(moved);
  return moved;
}

namespace {

std::array<vec3, 3> corners_at(const std::vector<std::vector<vec3>>& steps, uint32_t count,
                               const uint32_t* idx, float time) {
  const shutter_interval at = interval_at(count, time);
  const std::vector<vec3>& a = steps[at.step];
  const std::vector<vec3>& b = steps[at.step + 1];
  const float f = at.fraction;
  std::array<vec3, 3> corners;
  for (int k = 0; k < 3; ++k) corners[k] = (1.0f - f) * a[idx[k]] + f * b[idx[k]];
  return corners;
}

}  // namespace

std::array<vec3, 3> triangle_positions_at(const scene& s, uint32_t mesh, const uint32_t* idx, float time) {
  return corners_at(s.shutter.mesh_positions[mesh], s.shutter.steps, idx, time);
}

std::array<vec3, 3> triangle_normals_at(const scene& s, uint32_t mesh, const uint32_t* idx, float time) {
  return corners_at(s.shutter.mesh_normals[mesh], s.shutter.steps, idx, time);
}

}  // namespace kiln
