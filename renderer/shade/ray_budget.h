// The rays one camera sample may still spawn, and the cancel flag its ray tree polls. A scene of
// nested glass under a deep --max-depth makes one sample's tree exponential: the budget bounds its
// work, and polling inside the tree lets a cancel stop it without waiting for the sample to end.
// Depends on nothing but the standard library.
#pragma once

#include <atomic>
#include <cstdint>

namespace kiln {

// One per camera sample, shared by every branch of its tree (path_state points to it). Branches
// spend it depth first, so where a spent budget cuts the tree depends on the sample alone, never
// on threads or tiles.
struct ray_budget {
  // Spawned rays between two looks at the cancel flag: a few microseconds of work.
  static constexpr uint32_t poll_interval = 32;

  uint64_t rays_left = ~uint64_t(0);          // reflected, refracted and continued rays still allowed
  const std::atomic<bool>* cancel = nullptr;  // raised: spawn nothing more
  uint32_t until_poll = 0;                    // the first spawn looks at the flag
};

// Takes one secondary ray from the budget (null: unbounded). False when the budget is spent or a
// cancel has been seen: the caller then does not spawn the ray, and keeps what it has so far.
inline bool spend_ray(ray_budget* budget) {
  if (!budget) return true;
  if (budget->rays_left == 0) return false;
  if (budget->until_poll == 0) {
    budget->until_poll = ray_budget::poll_interval;
    if (budget->cancel && budget->cancel->load(std::memory_order_relaxed)) {
      budget->rays_left = 0;  // the rest of the tree is cut too
      return false;
    }
  }
  --budget->until_poll;
  --budget->rays_left;
  return true;
}

}  // namespace kiln
