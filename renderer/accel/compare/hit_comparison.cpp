#include "accel/compare/hit_comparison.h"

#include <algorithm>
#include <cmath>

#include "core/float_bits.h"
#include "geometry/quadric.h"
#include "geometry/triangle.h"
#include "geometry/watertight_triangle.h"

namespace kiln {

namespace {

float max_abs(const vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// Barycentric margin below which a hit counts as on an edge: a few thousand ulps of 1, wide enough
// for two different float formulations of the edge functions, tiny against any real triangle.
constexpr float edge_margin = 1e-4f;

}  // namespace

float hit_t_tolerance(const scene& s, const ray& r, const hit& h) {
  const instance& inst = s.instances[h.instance_id];
  const float floor = 1e-4f;  // cosine floor: a ray in the surface's plane has no defined t
  if (inst.kind == shape_kind::quadric) {
    // Both backends call the same double-precision quadric code; what is left is the hit point's
    // own error bound and the float rounding of t, seen along the ray.
    quadric_world_point w = quadric_world_hit(inst, s.quadrics[inst.shape], r, h.t, h.primitive_id);
    const float error =
        glm::length(w.error) + gamma_bound(8) * (max_abs(r.origin) + std::abs(h.t) * max_abs(r.direction));
    const float cosine = std::abs(glm::dot(r.direction, w.normal));
    return 4.0f * error / std::max(cosine, floor * glm::length(r.direction));
  }
  const mesh& m = s.meshes[inst.shape];

  // World space: the hit point's rounding error and a few ulps of the ray and the placement.
  surface_position p = triangle_hit_position(inst, m, h.primitive_id, h.u, h.v);
  const float world_error =
      glm::length(p.error) +
      gamma_bound(8) * (max_abs(r.origin) + std::abs(h.t) * max_abs(r.direction) +
                        max_abs(vec3(dvec3(inst.world_from_object[3]))) + max_abs(p.point));
  const float world_cosine = std::abs(glm::dot(r.direction, h.geometric_normal));
  const float world_dt = world_error / std::max(world_cosine, floor * glm::length(r.direction));

  // Object space: both backends solve for t there, where coordinates may be far larger than in
  // the world (a model authored in centimetres and scaled down); t is the same parameter. Embree
  // inverts its float 3x4 transform in float and runs Möller-Trumbore on precomputed edges; on
  // ToyCar (scale 1e-4, coordinates ~400) its t differs from the watertight test's by ~40 ulps of
  // the object-space coordinate magnitude, hence the wider gamma here. This is an empirical bound
  // on Embree's arithmetic, not a derived one.
  auto v = triangle_vertices(m, h.primitive_id);
  const vec3 origin = vec3(transform_point(inst.object_from_world, dvec3(r.origin)));
  const vec3 direction = vec3(transform_vector(inst.object_from_world, dvec3(r.direction)));
  const vec3 normal = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
  const float object_error = gamma_bound(64) * (max_abs(origin) + std::abs(h.t) * max_abs(direction) +
                                                std::max({max_abs(v[0]), max_abs(v[1]), max_abs(v[2])}));
  const float object_cosine = std::abs(glm::dot(direction, normal));
  const float object_dt = object_error / std::max(object_cosine, floor * glm::length(direction));

  return 4.0f * (world_dt + object_dt);
}

bool within_watertight_t_bound(const scene& s, const ray& r, const hit& h) {
  const instance& inst = s.instances[h.instance_id];
  if (inst.kind != shape_kind::mesh) return false;
  // The ray in object space as the grid moves it (instance_shapes.cpp), then the test's own bound.
  const vec3 origin = vec3(transform_point(inst.object_from_world, dvec3(r.origin)));
  const vec3 direction = vec3(transform_vector(inst.object_from_world, dvec3(r.direction)));
  auto v = triangle_vertices(s.meshes[inst.shape], h.primitive_id);
  const sheared_triangle st = shear_triangle(shear_ray(origin, direction), v[0], v[1], v[2]);
  const float det = st.e0 + st.e1 + st.e2;
  if (det == 0.0f) return false;
  return h.t - r.tmin <= watertight_t_bound(st, 1.0f / det);
}

bool hit_on_boundary(const scene& s, const ray& r, const hit& h) {
  // Triangle edges; a quadric hit's (u, v) are zero and mark no edge.
  const float b0 = 1.0f - h.u - h.v;
  if (s.instances[h.instance_id].kind == shape_kind::mesh && std::min({h.u, h.v, b0}) <= edge_margin)
    return true;
  const float tolerance = hit_t_tolerance(s, r, h);
  return h.t - r.tmin <= tolerance || r.tmax - h.t <= tolerance || within_watertight_t_bound(s, r, h);
}

hit_verdict compare_hits(const scene& s, const ray& r, const std::optional<hit>& a,
                         const std::optional<hit>& b) {
  if (!a && !b) return hit_verdict::agree;
  if (!a || !b) return hit_on_boundary(s, r, a ? *a : *b) ? hit_verdict::edge : hit_verdict::mismatch;
  const float tolerance = std::max(hit_t_tolerance(s, r, *a), hit_t_tolerance(s, r, *b));
  const bool same_t = std::abs(a->t - b->t) <= tolerance;
  if (a->instance_id == b->instance_id && a->primitive_id == b->primitive_id)
    return same_t ? hit_verdict::agree : hit_verdict::mismatch;
  if (same_t) return hit_verdict::tie;
  // One backend passed through an edge the other hit (a non-watertight test slipping between
  // two triangles) and went on to a farther surface.
  const hit& nearer = a->t < b->t ? *a : *b;
  return hit_on_boundary(s, r, nearer) ? hit_verdict::edge : hit_verdict::mismatch;
}

}  // namespace kiln
