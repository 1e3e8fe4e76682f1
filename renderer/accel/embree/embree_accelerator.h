// The Embree 3 traversal backend: one RTCScene per unique mesh, built once, and one
// RTC_GEOMETRY_TYPE_INSTANCE per placement in the top-level scene (Debian's Embree allows one
// instance level, which is why the loader flattens the node hierarchy).
// The only module that includes <embree3/rtcore.h>; errors never throw through Embree's callbacks.
#pragma once

#include <memory>
#include <string>

#include "accel/accelerator.h"
#include "accel/embree/embree_options.h"
#include "scene/scene.h"

namespace kiln {

// The Embree library's version, e.g. "3.13.5".
std::string embree_version();

class embree_accelerator final : public accelerator {
 public:
  // Builds every BVH. Throws kiln::error (render) when Embree reports an error.
  explicit embree_accelerator(const scene& s, const embree_options& options = {});
  ~embree_accelerator() override;
  embree_accelerator(const embree_accelerator&) = delete;
  embree_accelerator& operator=(const embree_accelerator&) = delete;

  std::optional<hit> intersect(const ray& r) const override;
  std::optional<hit> intersect_for_shadow(const ray& r) const override;
  bool occluded(const ray& r) const override;
  // Packets of the CPU's native width (rtcOccluded16, 8 or 4, a valid mask over the invalid rays
  // and the tail); quadrics answer in them too, each lane reading its own world ray.
  void occluded_batch(const ray* rays, size_t count, uint8_t* blocked) const override;
  // One rtcIntersect1M stream with the coherent flag (Embree traces it as packets of the CPU's
  // native width). Scenes with quadrics answer one ray at a time: their user geometry reads the
  // world ray from the intersect context, which holds one ray.
  void intersect_coherent(const ray* rays, size_t count, std::optional<hit>* out) const override;

  const embree_options& options() const { return options_; }
  // Bytes this accelerator's build added to Embree's memory (BVHs and its copies of the vertices
  // and indices) and the most it held during the build, from the device's memory monitor.
  size_t embree_bytes() const;
  size_t embree_peak_bytes() const;

  // Bare traversal for benchmarks: rtcIntersect1 (or rtcOccluded1 when occlusion) on each ray with
  // this accelerator's BVH and intersect context, and nothing else: no hit record, no shading.
  // Returns how many rays hit (or were blocked). The yardstick kiln's own queries are measured by.
  size_t trace_bare(const ray* rays, size_t count, bool occlusion) const;
  // The bare loop of intersect_coherent: the rays as one coherent rtcIntersect1M stream. Only
  // where streams_supported().
  size_t trace_bare_stream(const ray* rays, size_t count) const;
  // False for scenes with quadrics: their user geometry answers one ray at a time, so a stream
  // would miss every quadric.
  bool streams_supported() const;
  void throw_if_failed() const override;
  // Moves every instance (rtcSetGeometryTransform, then one commit of the top level) and refits the
  // changed meshes' BVHs to their new vertices (RTC_BUILD_QUALITY_REFIT); a mesh whose triangles
  // changed, or that moves for the first time, gets a BVH built for refitting instead. Throws
  // kiln::error (render) when Embree reports an error.
  bool update(const std::vector<uint32_t>& changed_meshes) override;

 private:
  // intersect(), with a quadric hit's normal only when quadric_normal is set (intersect_for_shadow).
  // Written into out, in place (see kiln_hit).
  void closest_hit(const ray& r, bool quadric_normal, std::optional<hit>& out) const;

  struct state;
  std::unique_ptr<state> state_;
  const scene& scene_;
  embree_options options_;
};

}  // namespace kiln
