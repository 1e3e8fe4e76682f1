// The ray-query interface every traversal backend implements (Embree, the uniform and adaptive
// grids, brute force) and the wrappers around one (compare, ray recording, camera-ray batches).
// Shading sees only this and the Scene, never a backend: two backends must return the same hit
// for the same ray, which is what makes one a correctness reference for the other.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/ray.h"

namespace kiln {

class accelerator {
 public:
  virtual ~accelerator() = default;

  // The closest hit with t in (r.tmin, r.tmax] (Embree's depth test), or empty for a miss or an
  // invalid ray.
  virtual std::optional<hit> intersect(const ray& r) const = 0;

  // intersect() for a shadow ray's walk past see-through surfaces: the same hit, except that a
  // backend may leave a quadric hit's geometric_normal zero. The walk reads only the instance of an
  // opaque blocker, and the surface point of a see-through one projects the hit itself; projecting
  // every blocking hit onto its quadric for a normal would be wasted.
  virtual std::optional<hit> intersect_for_shadow(const ray& r) const { return intersect(r); }

  // The closest hits of `count` rays that start close together and point alike (one tile's camera
  // rays), in order: out[i] is exactly intersect(rays[i]). A backend that traces such rays faster
  // together (Embree's ray streams) overrides it; the others answer one ray at a time.
  virtual void intersect_coherent(const ray* rays, size_t count, std::optional<hit>* out) const {
    for (size_t i = 0; i < count; ++i) out[i] = intersect(rays[i]);
  }

  // True when anything blocks the segment (r.tmin, r.tmax]. Invalid rays report not occluded.
  virtual bool occluded(const ray& r) const = 0;

  // occluded() of `count` rays at once (a wave's shadow rays), in order: blocked[i] is 1 exactly
  // when occluded(rays[i]) is true, else 0, invalid rays included. A backend that answers such rays
  // faster together (Embree's ray packets) overrides it; the others answer one ray at a time.
  virtual void occluded_batch(const ray* rays, size_t count, uint8_t* blocked) const {
    for (size_t i = 0; i < count; ++i) blocked[i] = occluded(rays[i]);
  }

  // Throws kiln::error (render) when the backend recorded a failure while answering queries; a
  // backend that reports errors through callbacks (Embree) cannot throw from inside a query.
  virtual void throw_if_failed() const {}

  // The next frame of a sequence: the scene this backend was built over changed in place (the
  // loader's gltf_sequence): every instance may have moved, and the meshes listed were built anew
  // (deformed: new positions, maybe other triangles). Brings the structure up to date and returns
  // true, or returns false when this backend cannot (or the instances no longer place the same
  // shapes); the caller then builds a new one. The grids and brute force rebuild.
  virtual bool update(const std::vector<uint32_t>& changed_meshes) {
    (void)changed_meshes;
    return false;
  }
};

}  // namespace kiln
