#include "accel/compare/hit_comparison.h"

#include "core/float_bits.h"
#include "geometry/triangle.h"

#include <algorithm>
#include <cmath>

namespace kiln {

namespace {

float max_abs(const vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// Barycentric margin below which a hit counts as on an edge: a few thousand ulps of 1, wide enough
// for two different float formulations of the edge functions, tiny against any real triangle.
constexpr float edge_margin = 1e-4f;

}  // namespace

float hit_t_tolerance(const scene& s, const ray& r, const hit& h) {
  const instance& inst = s.instances[h.instance_id];
  const mesh& m = s.meshes[inst.shape];
  surface_position p = triangle_hit_position(inst, m, h.primitive_id, h.u, h.v);
  // Moving the ray into object space in float: a few ulps of the origin, of the travelled
  // distance and of the instance's translation.
  const float transform_error =
      gamma_bound(8) * (max_abs(r.origin) + std::abs(h.t) * max_abs(r.direction) +
                        max_abs(vec3(dvec3(inst.world_from_object[3]))) + max_abs(p.point));
  const float offset = glm::length(p.error) + transform_error;
  const float cosine = std::abs(glm::dot(r.direction, h.geometric_normal));
  const float floor = 1e-4f * glm::length(r.direction);
  return 4.0f * offset / std::max(cosine, floor);
}

bool hit_on_boundary(const scene& s, const ray& r, const hit& h) {
  const float b0 = 1.0f - h.u - h.v;
  if (std::min({h.u, h.v, b0}) <= edge_margin) return true;
  const float tolerance = hit_t_tolerance(s, r, h);
  return h.t - r.tmin <= tolerance || r.tmax - h.t <= tolerance;
}

hit_verdict compare_hits(const scene& s, const ray& r, const std::optional<hit>& a, const std::optional<hit>& b) {
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
