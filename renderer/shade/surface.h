// The shading point: what shading needs to know about a hit, reconstructed from the Scene and the
// backend-neutral Hit (barycentric interpolation of normals and UVs for triangles).
// Depends on scene, geometry and the ray types; never on a backend.
#pragma once

#include "core/ray.h"
#include "scene/scene.h"

namespace kiln {

struct surface_point {
  vec3 position{0.0f};        // world space
  vec3 position_error{0.0f};  // per-axis bound on the rounding error of position
  vec3 geometric_normal{0.0f};  // unit, facing the incoming ray
  vec3 shading_normal{0.0f};    // unit, interpolated, on the same side as geometric_normal
  vec2 uv0{0.0f};
  vec2 uv1{0.0f};        // TEXCOORD_1 (TEXCOORD_0 when the mesh has none)
  vec4 color0{1.0f};     // COLOR_0, white when the mesh has none
  vec4 tangent{0.0f};    // world-space tangent (xyz, unnormalised) and handedness w; 0 when none
  uint32_t material = 0;
  bool front_face = true;  // the ray arrived on glTF's front side
};

// Interpolates attribute values with Embree's barycentric convention: (1-u-v)·a0 + u·a1 + v·a2.
template <typename T>
T interpolate(const T& a0, const T& a1, const T& a2, float u, float v) {
  return (1.0f - u - v) * a0 + u * a1 + v * a2;
}

// Builds the shading point of a hit for the ray that found it.
surface_point make_surface_point(const scene& s, const hit& h, const ray& r);

}  // namespace kiln
