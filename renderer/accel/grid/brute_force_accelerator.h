// The tie-breaker of accelerator tests: every triangle of every instance, in order, with the
// same object-space ray and watertight test as the grid. Slow by design; never used to render.
// Depends on scene, geometry and the accelerator interface.
#pragma once

#include <vector>

#include "accel/accelerator.h"
#include "accel/grid/grid_accelerator.h"
#include "scene/scene.h"

namespace kiln {

class brute_force_accelerator final : public accelerator {
 public:
  explicit brute_force_accelerator(const scene& s);

  std::optional<hit> intersect(const ray& r) const override;
  bool occluded(const ray& r) const override;

 private:
  const scene& scene_;
  std::vector<float_affine> object_from_world_;
};

}  // namespace kiln
