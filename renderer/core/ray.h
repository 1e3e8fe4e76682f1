// Rays and the backend-neutral hit record that every accelerator returns.
// Depends on core/math only: shading and accelerators share these types, nothing else.
#pragma once

#include <cstdint>

#include "core/math.h"

namespace kiln {

// Why a ray was traced. Accelerators ignore it; `kiln compare` reports its statistics per kind.
enum class ray_kind : uint8_t { camera, shadow, reflection, refraction, other };
constexpr int ray_kind_count = int(ray_kind::other) + 1;

// Which instances a ray may hit. A shadow ray through a scene with see-through surfaces is answered
// in steps (shade/direct_light.cpp): is anything that lets no light through in the way; if not, is
// anything see-through; only then is it walked. Every backend honours it (scene.h's ray_may_hit).
enum class ray_sees : uint8_t {
  everything,
  light_stoppers,    // only instances that let no light through
  see_through_only,  // only instances a shadow ray walks through (shade/shadow_transmittance.h)
};

// A ray segment o + t·d for t in [tmin, tmax]. Direction need not be unit length for
// accelerators, but kiln's own rays keep it unit so t is a distance.
struct ray {
  vec3 origin{0.0f};
  vec3 direction{0.0f, 0.0f, 1.0f};
  float tmin = 0.0f;
  float tmax = inf;
  ray_kind kind = ray_kind::other;
  ray_sees sees = ray_sees::everything;
  // When in the shutter the ray is traced (motion blur): 0 at its opening, 1 at its closing. Every
  // ray of a camera sample's path keeps the camera ray's time; 0 in a scene that does not move.
  float time = 0.0f;
};

// The largest origin or direction component a traversal backend takes: Embree 3.13's FLT_LARGE
// (RayK::valid() in kernels/common/ray.h). The scene checks keep kiln's rays far below it
// (scene/coordinate_range.h); this is the last line of defence.
constexpr float max_ray_component = 1.844e18f;

// True when a ray can be handed to a traversal backend: finite origin and direction within
// max_ray_component, a non-zero direction, and a non-empty, non-NaN extent. Embree's default
// build does not filter invalid rays (this one asserts on them), so this check is mandatory.
inline bool is_valid(const ray& r) {
  const vec3 o = glm::abs(r.origin), d = glm::abs(r.direction);
  // The comparisons are false for NaN, so they also refuse non-finite components.
  const bool in_range = o.x <= max_ray_component && o.y <= max_ray_component && o.z <= max_ray_component &&
                        d.x <= max_ray_component && d.y <= max_ray_component && d.z <= max_ray_component;
  return in_range && glm::dot(r.direction, r.direction) > 0.0f && !std::isnan(r.tmin) &&
         !std::isnan(r.tmax) && r.tmin >= 0.0f && r.tmin <= r.tmax;
}

// The closest intersection of a ray with the scene, identical across backends.
// (u, v) follow Embree's convention: p = (1-u-v)·p0 + u·p1 + v·p2 for triangles. For quadric
// instances primitive_id is the part (0 side or disk, 1 cap at zmin, 2 cap at zmax) and (u, v) the
// parametric UV of docs/quadrics.md.
struct hit {
  float t = inf;
  uint32_t instance_id = 0;   // index into scene.instances
  uint32_t primitive_id = 0;  // triangle index within the instance's mesh, or quadric part
  float u = 0.0f;             // barycentrics (Embree's convention) on a triangle; zero on a quadric
  float v = 0.0f;
  vec3 geometric_normal{0.0f};  // world space, unit length, front face by glTF winding
};

}  // namespace kiln
