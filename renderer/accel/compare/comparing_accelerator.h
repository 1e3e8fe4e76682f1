// A decorator that answers every query with the primary backend and asks the secondary the same
// question, so a render through it traces one set of camera rays and all their secondary rays
// against both backends. Statistics are kept per ray kind, per thread, and merged on request.
// Depends on the accelerator interface and hit_comparison only.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "accel/compare/hit_comparison.h"
#include "scene/scene.h"

namespace kiln {

const char* ray_kind_name(ray_kind k);

// What one ray kind's queries showed.
struct kind_statistics {
  uint64_t rays = 0;  // closest-hit and occlusion queries
  uint64_t closest_hit_queries = 0;
  uint64_t occlusion_queries = 0;
  uint64_t closest_hit_mismatches = 0;
  uint64_t occlusion_mismatches = 0;
  uint64_t ties = 0;             // different primitives at the same t
  uint64_t edge_cases = 0;       // edge grazes and hits at the segment's ends
  double max_relative_dt = 0.0;  // max |Δt|/t over hits on the same primitive

  void merge(const kind_statistics& o);
};

// One disagreement, kept for the report.
struct mismatch_example {
  ray query;
  bool occlusion = false;
  std::optional<hit> primary, secondary;
  bool primary_occluded = false, secondary_occluded = false;
};

struct comparison_statistics {
  std::array<kind_statistics, ray_kind_count> by_kind{};
  std::vector<mismatch_example> examples;  // the first few

  uint64_t mismatches() const;
};

// The verdict of `kiln compare`: true when the closest-hit and occlusion mismatches (ties and edge
// cases are not mismatches) number at most max_mismatches.
bool backends_agree(const comparison_statistics& s, uint64_t max_mismatches);

class comparing_accelerator final : public accelerator {
 public:
  comparing_accelerator(const scene& s, const accelerator& primary, const accelerator& secondary);
  ~comparing_accelerator() override;

  std::optional<hit> intersect(const ray& r) const override;
  bool occluded(const ray& r) const override;
  void occluded_batch(const ray* rays, size_t count, uint8_t* blocked) const override;
  void throw_if_failed() const override {
    primary_.throw_if_failed();
    secondary_.throw_if_failed();
  }

  // Merged statistics of every query so far (call when no query is running).
  comparison_statistics statistics() const;

 private:
  // Counts one occlusion query whose backends answered a (primary) and b (secondary).
  void count_occlusion(const ray& r, bool a, bool b) const;

  struct per_thread;
  const scene& scene_;
  const accelerator& primary_;
  const accelerator& secondary_;
  std::unique_ptr<per_thread> threads_;
};

}  // namespace kiln
