// Every ray shading spawns from a surface, made in one place: its origin pushed off the surface by
// the hit's error bound (core/float_bits.h's offset_ray_origin, pbrt-v4's OffsetRayOrigin) to the
// side the ray leaves by, never by a global epsilon, and the surface's time in the shutter kept.
// Depends on core and shade/surface.h only.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/float_bits.h"
#include "core/ray.h"
#include "shade/surface.h"

namespace kiln {

// A ray leaving sp along the unit direction (mirror, refraction, the continuation behind a BLEND
// surface, a shadow ray toward a light behind a diffusely transmitting surface).
inline ray spawn_ray(const surface_point& sp, const vec3& direction, ray_kind kind) {
  ray r;
  r.origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, direction);
  r.direction = direction;
  r.kind = kind;
  r.time = sp.time;
  return r;
}

// A shadow ray toward a light above the smooth surface the vertex normals describe: it starts on
// that surface (sp.smooth_position), always off the facet's front, so a light just below the
// facet's plane is still above where the ray starts and a low-poly mesh does not shadow itself
// along its terminator.
inline ray spawn_shadow_ray_above(const surface_point& sp, const vec3& direction) {
  ray r;
  r.origin =
      offset_ray_origin(sp.smooth_position, sp.position_error, sp.geometric_normal, sp.geometric_normal);
  r.direction = direction;
  r.kind = ray_kind::shadow;
  r.time = sp.time;
  return r;
}

// Moves r on past the surface sp it hit (a culled back face, a see-through blocker of a shadow
// ray), keeping its direction, kind and far end. False when nothing of the segment is left.
inline bool continue_past(const surface_point& sp, ray& r) {
  const vec3 origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, r.direction);
  if (!std::isinf(r.tmax)) r.tmax = std::max(r.tmax - glm::length(origin - r.origin), 0.0f);
  r.origin = origin;
  return r.tmax > 0.0f;
}

}  // namespace kiln
