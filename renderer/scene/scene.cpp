#include "scene/scene.h"

namespace kiln {

bounds3 world_bounds(const scene& s) {
  bounds3 result;
  for (const instance& inst : s.instances) {
    const mesh& m = s.meshes[inst.shape];
    result.extend(transform_bounds(inst.world_from_object, m.bounds));
  }
  return result;
}

void finish_instance_transform(instance& inst) {
  inst.object_from_world = glm::inverse(inst.world_from_object);
  inst.world_from_object_normal = normal_matrix(inst.world_from_object);
}

}  // namespace kiln
