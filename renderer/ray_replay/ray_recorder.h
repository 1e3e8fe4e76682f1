// An accelerator wrapper that records every query a render makes, by ray kind and query type, so a
// benchmark can replay exactly those rays through a bare traversal loop. Backend-neutral: it sees
// only the accelerator interface. Not for production renders (it stores every ray).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "accel/accelerator.h"

namespace kiln {

// The rays of one render, split by kind; closest-hit queries and occlusion queries apart.
struct recorded_rays {
  std::array<std::vector<ray>, ray_kind_count> intersect;
  std::array<std::vector<ray>, ray_kind_count> occluded;

  size_t total() const;
};

class ray_recorder final : public accelerator {
 public:
  explicit ray_recorder(const accelerator& inner);
  ~ray_recorder() override;

  std::optional<hit> intersect(const ray& r) const override;
  bool occluded(const ray& r) const override;
  void occluded_batch(const ray* rays, size_t count, uint8_t* blocked) const override;
  void throw_if_failed() const override { inner_.throw_if_failed(); }

  // Every query so far, merged over threads (call when no query is running). The order within a
  // kind is unspecified; benchmarks do not depend on it.
  recorded_rays rays() const;

 private:
  struct per_thread;
  const accelerator& inner_;
  std::unique_ptr<per_thread> threads_;
};

}  // namespace kiln
