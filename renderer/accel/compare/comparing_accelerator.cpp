#include "accel/compare/comparing_accelerator.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <mutex>

namespace kiln {

namespace {

constexpr size_t max_examples = 16;

}  // namespace

const char* ray_kind_name(ray_kind k) {
  switch (k) {
    case ray_kind::camera:
      return "camera";
    case ray_kind::shadow:
      return "shadow";
    case ray_kind::reflection:
      return "reflection";
    case ray_kind::refraction:
      return "refraction";
    case ray_kind::other:
      return "other";
  }
  return "other";
}

void kind_statistics::merge(const kind_statistics& o) {
  rays += o.rays;
  closest_hit_queries += o.closest_hit_queries;
  occlusion_queries += o.occlusion_queries;
  closest_hit_mismatches += o.closest_hit_mismatches;
  occlusion_mismatches += o.occlusion_mismatches;
  ties += o.ties;
  edge_cases += o.edge_cases;
  max_relative_dt = std::max(max_relative_dt, o.max_relative_dt);
}

uint64_t comparison_statistics::mismatches() const {
  uint64_t total = 0;
  for (const kind_statistics& k : by_kind) total += k.closest_hit_mismatches + k.occlusion_mismatches;
  return total;
}

bool backends_agree(const comparison_statistics& s, uint64_t max_mismatches) {
  return s.mismatches() <= max_mismatches;
}

// Counters live per thread (no contention on the render's hot path); examples are rare and
// share one list behind a mutex.
struct comparing_accelerator::per_thread {
  tbb::enumerable_thread_specific<std::array<kind_statistics, ray_kind_count>> stats;
  std::mutex examples_mutex;
  std::vector<mismatch_example> examples;

  void keep(const mismatch_example& e) {
    std::lock_guard<std::mutex> lock(examples_mutex);
    if (examples.size() < max_examples) examples.push_back(e);
  }
};

comparing_accelerator::comparing_accelerator(const scene& s, const accelerator& primary,
                                             const accelerator& secondary)
    : scene_(s), primary_(primary), secondary_(secondary), threads_(std::make_unique<per_thread>()) {}

comparing_accelerator::~comparing_accelerator() = default;

std::optional<hit> comparing_accelerator::intersect(const ray& r) const {
  std::optional<hit> a = primary_.intersect(r);
  std::optional<hit> b = secondary_.intersect(r);
  kind_statistics& k = threads_->stats.local()[size_t(r.kind)];
  ++k.rays;
  ++k.closest_hit_queries;
  switch (compare_hits(scene_, r, a, b)) {
    case hit_verdict::agree:
      if (a && b && a->t > 0.0f)
        k.max_relative_dt = std::max(k.max_relative_dt, double(std::abs(a->t - b->t)) / a->t);
      break;
    case hit_verdict::tie:
      ++k.ties;
      break;
    case hit_verdict::edge:
      ++k.edge_cases;
      break;
    case hit_verdict::mismatch:
      ++k.closest_hit_mismatches;
      threads_->keep(mismatch_example{r, false, a, b, false, false});
      break;
  }
  return a;
}

bool comparing_accelerator::occluded(const ray& r) const {
  const bool a = primary_.occluded(r);
  count_occlusion(r, a, secondary_.occluded(r));
  return a;
}

void comparing_accelerator::occluded_batch(const ray* rays, size_t count, uint8_t* blocked) const {
  // Each backend answers the whole batch its own way (Embree in packets), so the packets are what
  // is held to the other backend.
  thread_local std::vector<uint8_t> secondary;
  secondary.resize(count);
  primary_.occluded_batch(rays, count, blocked);
  secondary_.occluded_batch(rays, count, secondary.data());
  for (size_t i = 0; i < count; ++i) count_occlusion(rays[i], blocked[i] != 0, secondary[i] != 0);
}

void comparing_accelerator::count_occlusion(const ray& r, bool a, bool b) const {
  kind_statistics& k = threads_->stats.local()[size_t(r.kind)];
  ++k.rays;
  ++k.occlusion_queries;
  if (a != b) {
    // Find the blocker the occluded side saw: a blocker on an edge or at the segment's end is a
    // rounding case, not a failure.
    std::optional<hit> blocker = a ? primary_.intersect(r) : secondary_.intersect(r);
    if (blocker && hit_on_boundary(scene_, r, *blocker)) {
      ++k.edge_cases;
    } else {
      ++k.occlusion_mismatches;
      threads_->keep(mismatch_example{r, true, a ? blocker : std::nullopt, b ? blocker : std::nullopt, a, b});
    }
  }
}

comparison_statistics comparing_accelerator::statistics() const {
  comparison_statistics out;
  for (const auto& local : threads_->stats)
    for (int i = 0; i < ray_kind_count; ++i) out.by_kind[size_t(i)].merge(local[size_t(i)]);
  out.examples = threads_->examples;
  return out;
}

}  // namespace kiln
