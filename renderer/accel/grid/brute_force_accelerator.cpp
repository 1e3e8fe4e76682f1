#include "accel/grid/brute_force_accelerator.h"

#include "geometry/triangle.h"
#include "geometry/watertight_triangle.h"

namespace kiln {

brute_force_accelerator::brute_force_accelerator(const scene& s) : scene_(s) {
  for (const instance& inst : s.instances)
    object_from_world_.push_back(to_float_affine(inst.object_from_world));
}

namespace {

// Calls f(instance, primitive, hit) for every triangle the ray meets with t in (tmin, tmax(...)],
// instance by instance in order; f returns true to stop. tmax is asked again before each test so
// a closest-hit search can shrink it.
template <typename upper_bound, typename function>
void for_each_triangle_hit(const scene& s, const std::vector<float_affine>& object_from_world, const ray& r,
                           const upper_bound& tmax, const function& f) {
  for (uint32_t i = 0; i < s.instances.size(); ++i) {
    const mesh& m = s.meshes[s.instances[i].shape];
    vec3 origin, direction;
    to_object_space(object_from_world[i], r, origin, direction);
    const sheared_ray sheared = shear_ray(origin, direction);
    for (uint32_t p = 0; p < m.triangle_count(); ++p) {
      auto v = triangle_vertices(m, p);
      triangle_hit th;
      if (intersect_watertight(sheared, v[0], v[1], v[2], r.tmin, tmax(), th) && f(i, p, th)) return;
    }
  }
}

}  // namespace

std::optional<hit> brute_force_accelerator::intersect(const ray& r) const {
  if (!is_valid(r)) return std::nullopt;
  std::optional<hit> best;
  // Visiting in (instance, primitive) order and replacing only on a strictly smaller t gives the
  // grid's tie rule: the lowest (instance, primitive) among equal t.
  for_each_triangle_hit(
      scene_, object_from_world_, r, [&] { return best ? best->t : r.tmax; },
      [&](uint32_t i, uint32_t p, const triangle_hit& th) {
        if (!best || th.t < best->t) best = hit{th.t, i, p, th.u, th.v, vec3(0.0f)};
        return false;
      });
  if (best) {
    const instance& inst = scene_.instances[best->instance_id];
    best->geometric_normal = triangle_world_normal(inst, scene_.meshes[inst.shape], best->primitive_id);
  }
  return best;
}

bool brute_force_accelerator::occluded(const ray& r) const {
  if (!is_valid(r)) return false;
  bool blocked = false;
  for_each_triangle_hit(
      scene_, object_from_world_, r, [&] { return r.tmax; },
      [&](uint32_t, uint32_t, const triangle_hit&) { return blocked = true; });
  return blocked;
}

}  // namespace kiln
