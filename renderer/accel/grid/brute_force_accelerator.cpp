#include "accel/grid/brute_force_accelerator.h"

#include "accel/grid/instance_shapes.h"

namespace kiln {

brute_force_accelerator::brute_force_accelerator(const scene& s) : scene_(s) {
  for (const instance& inst : s.instances)
    object_from_world_.push_back(to_float_affine(inst.object_from_world));
}

std::optional<hit> brute_force_accelerator::intersect(const ray& r) const {
  if (!is_valid(r)) return std::nullopt;
  traversal_counters counters;
  // Visiting instances in order and replacing only on a strictly smaller t gives the grid's tie
  // rule: the lowest (instance, primitive) among equal t.
  std::optional<shape_hit> best;
  uint32_t best_instance = 0;
  for (uint32_t i = 0; i < scene_.instances.size(); ++i) {
    vec3 origin, direction;
    to_object_space(object_from_world_[i], r, origin, direction);
    std::optional<shape_hit> h =
        intersect_instance_shape(scene_, i, r, origin, direction, best ? best->t : r.tmax, nullptr, counters);
    if (h && (!best || h->t < best->t)) {
      best = h;
      best_instance = i;
    }
  }
  if (!best) return std::nullopt;
  return finish_hit(scene_, r, best->t, best_instance, best->primitive, best->u, best->v);
}

bool brute_force_accelerator::occluded(const ray& r) const {
  if (!is_valid(r)) return false;
  traversal_counters counters;
  for (uint32_t i = 0; i < scene_.instances.size(); ++i) {
    vec3 origin, direction;
    to_object_space(object_from_world_[i], r, origin, direction);
    if (occluded_instance_shape(scene_, i, r, origin, direction, nullptr, counters)) return true;
  }
  return false;
}

}  // namespace kiln
