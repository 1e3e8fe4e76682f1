#include "scene/scene.h"

#include <cmath>

namespace kiln {

bounds3 world_bounds(const scene& s) {
  bounds3 result;
  for (const instance& inst : s.instances) {
    const bounds3& b =
        inst.kind == shape_kind::quadric ? s.quadrics[inst.shape].bounds : s.meshes[inst.shape].bounds;
    result.extend(transform_bounds(inst.world_from_object, b));
  }
  return result;
}

void finish_instance_transform(instance& inst) {
  inst.object_from_world = glm::inverse(inst.world_from_object);
  inst.world_from_object_normal = normal_matrix(inst.world_from_object);
  const dmat3 linear(inst.world_from_object);
  inst.abs_linear = dmat3(glm::abs(linear[0]), glm::abs(linear[1]), glm::abs(linear[2]));
  const double determinant = glm::determinant(linear);
  inst.mirrored = determinant < 0.0;
  inst.mean_scale = std::cbrt(std::abs(determinant));
}

}  // namespace kiln
