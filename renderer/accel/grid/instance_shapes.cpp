#include "accel/grid/instance_shapes.h"

#include "geometry/quadric.h"
#include "geometry/triangle.h"
#include "geometry/watertight_triangle.h"

namespace kiln {

namespace {

// The closest quadric hit of the world ray in (tmin, tmax), with the ray moved to object space
// in double exactly as the Embree user-geometry callbacks do, so both backends find the same t.
std::optional<quadric_ray_hit> intersect_quadric_instance(const scene& s, const instance& inst, const ray& r,
                                                          float tmax) {
  const dvec3 o = transform_point(inst.object_from_world, dvec3(r.origin));
  const dvec3 d = transform_vector(inst.object_from_world, dvec3(r.direction));
  return intersect_quadric(s.quadrics[inst.shape], o, d, r.tmin, tmax);
}

// Every triangle of the mesh in primitive order (the brute-force reference): the closest hit, the
// lowest primitive among equal t, or with any_hit the first one found.
std::optional<shape_hit> intersect_all_triangles(const mesh& m, const vec3& origin, const vec3& direction,
                                                 float tmin, float tmax, const alpha_filter& alpha,
                                                 bool any_hit, traversal_counters& counters) {
  const sheared_ray sheared = shear_ray(origin, direction);
  std::optional<shape_hit> best;
  for (uint32_t p = 0; p < m.triangle_count(); ++p) {
    ++counters.items_tested;
    auto v = triangle_vertices(m, p);
    triangle_hit th;
    if (!intersect_watertight(sheared, v[0], v[1], v[2], tmin, best ? best->t : tmax, th)) continue;
    if (alpha.rejects(p, th.u, th.v)) continue;
    if (!best || th.t < best->t) best = shape_hit{th.t, p, th.u, th.v};
    if (any_hit) break;
  }
  return best;
}

}  // namespace

bounds3 instance_object_bounds(const scene& s, const instance& inst) {
  return inst.kind == shape_kind::quadric ? s.quadrics[inst.shape].bounds : s.meshes[inst.shape].bounds;
}

std::optional<shape_hit> intersect_instance_shape(const scene& s, uint32_t instance_id, const ray& world_ray,
                                                  const vec3& origin, const vec3& direction, float tmax,
                                                  const mesh_grid* grid, traversal_counters& counters) {
  const instance& inst = s.instances[instance_id];
  if (!ray_may_hit(s, inst, world_ray.kind, world_ray.sees)) return std::nullopt;
  switch (inst.kind) {
    case shape_kind::mesh: {
      const mesh& m = s.meshes[inst.shape];
      const alpha_filter alpha = alpha_filter_for(s, instance_id);
      if (!grid)
        return intersect_all_triangles(m, origin, direction, world_ray.tmin, tmax, alpha, false, counters);
      shape_hit h;
      if (intersect_mesh_grid(*grid, m, origin, direction, world_ray.tmin, tmax, h, counters, alpha))
        return h;
      return std::nullopt;
    }
    case shape_kind::quadric: {
      ++counters.items_tested;
      std::optional<quadric_ray_hit> q = intersect_quadric_instance(s, inst, world_ray, tmax);
      if (!q) return std::nullopt;
      return shape_hit{float(q->t), q->part, 0.0f, 0.0f};
    }
  }
  return std::nullopt;
}

bool occluded_instance_shape(const scene& s, uint32_t instance_id, const ray& world_ray, const vec3& origin,
                             const vec3& direction, const mesh_grid* grid, traversal_counters& counters) {
  const instance& inst = s.instances[instance_id];
  if (!ray_may_hit(s, inst, world_ray.kind, world_ray.sees)) return false;
  switch (inst.kind) {
    case shape_kind::mesh: {
      const mesh& m = s.meshes[inst.shape];
      const alpha_filter alpha = alpha_filter_for(s, instance_id);
      if (!grid)
        return intersect_all_triangles(m, origin, direction, world_ray.tmin, world_ray.tmax, alpha, true,
                                       counters)
            .has_value();
      return occluded_mesh_grid(*grid, m, origin, direction, world_ray.tmin, world_ray.tmax, counters, alpha);
    }
    case shape_kind::quadric:
      ++counters.items_tested;
      return intersect_quadric_instance(s, inst, world_ray, world_ray.tmax).has_value();
  }
  return false;
}

hit finish_hit(const scene& s, const ray& r, float t, uint32_t instance_id, uint32_t primitive, float u,
               float v) {
  const instance& inst = s.instances[instance_id];
  hit h;
  h.t = t;
  h.instance_id = instance_id;
  h.primitive_id = primitive;
  if (inst.kind == shape_kind::quadric) {
    // Part in primitive_id, normal from the gradient, (u, v) zero: as the Embree backend.
    h.geometric_normal = quadric_world_normal(inst, s.quadrics[inst.shape], r, t, primitive);
    return h;
  }
  h.u = u;
  h.v = v;
  h.geometric_normal = triangle_world_normal(inst, s.meshes[inst.shape], primitive);
  return h;
}

}  // namespace kiln
