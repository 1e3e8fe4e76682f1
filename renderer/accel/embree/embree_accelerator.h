// The Embree 3 traversal backend: one RTCScene per unique mesh, built once, and one
// RTC_GEOMETRY_TYPE_INSTANCE per placement in the top-level scene (Debian's Embree allows one
// instance level, which is why the loader flattens the node hierarchy).
// The only module that includes <embree3/rtcore.h>; errors never throw through Embree's callbacks.
#pragma once

#include <memory>
#include <string>

#include "accel/accelerator.h"
#include "scene/scene.h"

namespace kiln {

// The Embree library's version, e.g. "3.13.5".
std::string embree_version();

class embree_accelerator final : public accelerator {
 public:
  // Builds every BVH. Throws kiln::error (render) when Embree reports an error.
  explicit embree_accelerator(const scene& s);
  ~embree_accelerator() override;
  embree_accelerator(const embree_accelerator&) = delete;
  embree_accelerator& operator=(const embree_accelerator&) = delete;

  std::optional<hit> intersect(const ray& r) const override;
  bool occluded(const ray& r) const override;

  // Bare traversal for benchmarks: rtcIntersect1 (or rtcOccluded1 when occlusion) on each ray with
  // this accelerator's BVH and intersect context, and nothing else: no hit record, no shading.
  // Returns how many rays hit (or were blocked). The yardstick kiln's own queries are measured by.
  size_t trace_bare(const ray* rays, size_t count, bool occlusion) const;
  void throw_if_failed() const override;

 private:
  struct state;
  std::unique_ptr<state> state_;
  const scene& scene_;
};

}  // namespace kiln
