// Triangle geometry shared by every backend and by shading: vertex fetch, the geometric normal
// in world space, and the hit point reconstructed from barycentrics with its rounding-error bound.
// Depends on core and scene only.
#pragma once

#include <array>

#include "core/float_bits.h"
#include "scene/scene.h"

namespace kiln {

inline std::array<vec3, 3> triangle_vertices(const mesh& m, uint32_t primitive) {
  const uint32_t* idx = &m.indices[size_t(primitive) * 3];
  return {m.positions[idx[0]], m.positions[idx[1]], m.positions[idx[2]]};
}

// Unit geometric normal in world space. Front face = counter-clockwise in object space, carried
// through the normal matrix so that mirroring transforms keep glTF's front face.
inline vec3 triangle_world_normal(const instance& inst, const mesh& m, uint32_t primitive) {
  auto p = triangle_vertices(m, primitive);
  dvec3 n_object = glm::cross(dvec3(p[1] - p[0]), dvec3(p[2] - p[0]));
  return vec3(glm::normalize(inst.world_from_object_normal * n_object));
}

// A world-space point on a surface and a per-axis bound on its absolute rounding error.
struct surface_position {
  vec3 point{0.0f};
  vec3 error{0.0f};
};

// The hit point from barycentrics (u, v) rather than o + t·d: it lies on the triangle's plane up
// to a few ulps (pbrt-v4 Triangle::InteractionFromIntersection), then moves to world space in double.
inline surface_position triangle_hit_position(const instance& inst, const mesh& m, uint32_t primitive,
                                              float u, float v) {
  auto p = triangle_vertices(m, primitive);
  float b0 = 1.0f - u - v;
  vec3 obj = b0 * p[0] + u * p[1] + v * p[2];
  vec3 obj_error = gamma_bound(7) * (glm::abs(b0 * p[0]) + glm::abs(u * p[1]) + glm::abs(v * p[2]));
  dvec3 world = transform_point(inst.world_from_object, dvec3(obj));
  const dmat3& abs_linear = inst.abs_linear;
  dvec3 world_error = abs_linear * dvec3(obj_error) * (1.0 + 4.0 * gamma_bound(3)) +
                      double(gamma_bound(3)) *
                          (abs_linear * glm::abs(dvec3(obj)) + glm::abs(dvec3(inst.world_from_object[3])));
  surface_position result;
  result.point = vec3(world);
  // Rounding the double result to float adds half an ulp per axis.
  result.error = vec3(world_error) + glm::abs(result.point) * machine_epsilon * 2.0f;
  return result;
}

}  // namespace kiln
