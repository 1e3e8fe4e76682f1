// Intersection of a world ray with one instance's shape, whatever its kind: a mesh through its
// object-level grid (alpha masks applied), a quadric through the same double-precision function
// the Embree user geometry calls. Shared by the grid and brute-force backends so that shape kinds
// meet traversal in one place. Depends on scene, geometry and the grid core; never on Embree.
#pragma once

#include <optional>

#include "accel/grid/mesh_grid.h"
#include "core/ray.h"
#include "scene/scene.h"

namespace kiln {

// Object-space bounds of an instance's shape.
bounds3 instance_object_bounds(const scene& s, const instance& inst);

// The closest hit of the instance's shape with t in the ray's (tmin, tmax); origin and direction
// are the ray in the instance's object space (float, as Embree moves it for triangles). grid is
// the mesh's object grid, or nullptr to test every triangle (brute force); unused for quadrics.
std::optional<shape_hit> intersect_instance_shape(const scene& s, uint32_t instance_id, const ray& world_ray,
                                                  const vec3& origin, const vec3& direction, float tmax,
                                                  const mesh_grid* grid, traversal_counters& counters);

// True when the instance's shape blocks the ray anywhere in (tmin, tmax).
bool occluded_instance_shape(const scene& s, uint32_t instance_id, const ray& world_ray, const vec3& origin,
                             const vec3& direction, const mesh_grid* grid, traversal_counters& counters);

// The backend-neutral hit for a shape hit, filled exactly as the Embree backend fills it
// (triangle normal through the normal matrix; quadric normal in double, (u, v) zero).
hit finish_hit(const scene& s, const ray& r, float t, uint32_t instance_id, uint32_t primitive, float u,
               float v);

}  // namespace kiln
