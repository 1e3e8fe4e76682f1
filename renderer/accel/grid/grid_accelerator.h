// The in-house reference backend: nested grids. One object-level grid per unique mesh (built
// once, so memory grows with unique geometry, not with instances) and a top-level grid over the
// instances' world bounds. A ray reaching an instance is moved into object space with the
// instance's float object_from_world, as Embree moves rays into its instanced scenes, and the
// same watertight triangle test answers there. With max_depth = 0 every grid is uniform; with
// max_depth > 0 crowded cells are subdivided (the adaptive grid).
// Depends on scene, geometry and the accelerator interface; never on Embree.
#pragma once

#include <vector>

#include "accel/accelerator.h"
#include "accel/grid/grid.h"
#include "accel/grid/mesh_grid.h"
#include "scene/scene.h"

namespace kiln {

// An instance's ray transform in float, as Embree stores it (3x4, column major).
struct float_affine {
  mat3 linear{1.0f};
  vec3 translation{0.0f};
};

class grid_accelerator final : public accelerator {
 public:
  grid_accelerator(const scene& s, const grid_options& options);

  std::optional<hit> intersect(const ray& r) const override;
  bool occluded(const ray& r) const override;

  // Intersect with work counters (cells visited, items tested), for tests and benchmarks.
  std::optional<hit> intersect(const ray& r, traversal_counters& counters) const;

  grid_statistics statistics() const;

 private:
  // The object-level grid of a mesh instance; nullptr for quadric instances.
  const mesh_grid* mesh_grid_of(uint32_t instance_id) const;

  const scene& scene_;
  std::vector<mesh_grid> mesh_grids_;            // one per scene mesh; empty when unused
  std::vector<float_affine> object_from_world_;  // one per instance
  grid top_;                                     // items are instance ids
};

// The object-space ray of an instance: origin and direction through its float transform, the same
// t parameter (the direction is not renormalised, as in Embree).
void to_object_space(const float_affine& object_from_world, const ray& r, vec3& origin, vec3& direction);

float_affine to_float_affine(const dmat4& m);

}  // namespace kiln
