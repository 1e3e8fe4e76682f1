// The object-level grid of one mesh: its triangles in their own object space, inserted by the
// exact triangle-box test, intersected with the watertight triangle test. Built once per unique
// mesh however many instances place it. Depends on scene, geometry and the grid core.
#pragma once

#include "accel/grid/grid.h"
#include "accel/grid/grid_traversal.h"
#include "scene/scene.h"

namespace kiln {

struct mesh_grid {
  grid cells;
};

// A hit on one shape in its object space. Among hits at exactly the same t the lowest
// primitive id wins, so the grid and the brute-force loop agree on ties whatever their order.
struct shape_hit {
  float t = inf;
  uint32_t primitive = UINT32_MAX;
  float u = 0.0f;
  float v = 0.0f;
};

// The glTF alpha-mask rule for the instance being traversed, applied to every candidate triangle
// exactly as the Embree backend's filter functions do. world == nullptr: nothing is masked.
struct alpha_filter {
  const scene* world = nullptr;
  uint32_t instance = 0;

  bool rejects(uint32_t primitive, float u, float v) const;
};

// The filter for an instance: active only when its material uses alphaMode MASK.
alpha_filter alpha_filter_for(const scene& s, uint32_t instance_id);

mesh_grid build_mesh_grid(const mesh& m, const grid_options& options);

// Closest triangle of the object-space ray with t in (tmin, tmax]; updates best and returns true
// when it found one.
bool intersect_mesh_grid(const mesh_grid& g, const mesh& m, const vec3& origin, const vec3& direction,
                         float tmin, float tmax, shape_hit& best, traversal_counters& counters,
                         const alpha_filter& alpha = {});

// True when any triangle meets the object-space ray with t in (tmin, tmax].
bool occluded_mesh_grid(const mesh_grid& g, const mesh& m, const vec3& origin, const vec3& direction,
                        float tmin, float tmax, traversal_counters& counters, const alpha_filter& alpha = {});

}  // namespace kiln
