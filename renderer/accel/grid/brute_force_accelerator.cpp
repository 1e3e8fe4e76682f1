#include "accel/grid/brute_force_accelerator.h"

#include "geometry/triangle.h"
#include "geometry/watertight_triangle.h"

namespace kiln {

brute_force_accelerator::brute_force_accelerator(const scene& s) : scene_(s) {
  for (const instance& inst : s.instances) object_from_world_.push_back(to_float_affine(inst.object_from_world));
}

std::optional<hit> brute_force_accelerator::intersect(const ray& r) const {
  if (!is_valid(r)) return std::nullopt;
  std::optional<hit> best;
  for (uint32_t i = 0; i < scene_.instances.size(); ++i) {
    const instance& inst = scene_.instances[i];
    const mesh& m = scene_.meshes[inst.shape];
    vec3 origin, direction;
    to_object_space(object_from_world_[i], r, origin, direction);
    const sheared_ray sheared = shear_ray(origin, direction);
    for (uint32_t p = 0; p < m.triangle_count(); ++p) {
      auto v = triangle_vertices(m, p);
      triangle_hit th;
      // Visiting in (instance, primitive) order and replacing only on a strictly smaller t gives
      // the grid's tie rule: the lowest (instance, primitive) among equal t.
      if (!intersect_watertight(sheared, v[0], v[1], v[2], r.tmin, best ? best->t : r.tmax, th)) continue;
      if (best && !(th.t < best->t)) continue;
      best = hit{th.t, i, p, th.u, th.v, vec3(0.0f)};
    }
  }
  if (best) {
    const instance& inst = scene_.instances[best->instance_id];
    best->geometric_normal = triangle_world_normal(inst, scene_.meshes[inst.shape], best->primitive_id);
  }
  return best;
}

bool brute_force_accelerator::occluded(const ray& r) const {
  if (!is_valid(r)) return false;
  for (uint32_t i = 0; i < scene_.instances.size(); ++i) {
    const mesh& m = scene_.meshes[scene_.instances[i].shape];
    vec3 origin, direction;
    to_object_space(object_from_world_[i], r, origin, direction);
    const sheared_ray sheared = shear_ray(origin, direction);
    for (uint32_t p = 0; p < m.triangle_count(); ++p) {
      auto v = triangle_vertices(m, p);
      triangle_hit th;
      if (intersect_watertight(sheared, v[0], v[1], v[2], r.tmin, r.tmax, th)) return true;
    }
  }
  return false;
}

}  // namespace kiln
