// The ray-query interface every traversal backend implements (Embree now, the grid later).
// Shading sees only this and the Scene, never a backend: two backends must return the same hit
// for the same ray, which is what makes one a correctness reference for the other.
#pragma once

#include <optional>

#include "core/ray.h"

namespace kiln {

class accelerator {
 public:
  virtual ~accelerator() = default;

  // The closest hit with t in (r.tmin, r.tmax] (Embree's depth test), or empty for a miss or an
  // invalid ray.
  virtual std::optional<hit> intersect(const ray& r) const = 0;

  // True when anything blocks the segment (r.tmin, r.tmax]. Invalid rays report not occluded.
  virtual bool occluded(const ray& r) const = 0;

  // Throws kiln::error (render) when the backend recorded a failure while answering queries; a
  // backend that reports errors through callbacks (Embree) cannot throw from inside a query.
  virtual void throw_if_failed() const {}
};

}  // namespace kiln
