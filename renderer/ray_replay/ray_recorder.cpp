#include "ray_replay/ray_recorder.h"

#include <tbb/enumerable_thread_specific.h>

namespace kiln {

size_t recorded_rays::total() const {
  size_t n = 0;
  for (const auto& v : intersect) n += v.size();
  for (const auto& v : occluded) n += v.size();
  return n;
}

// One buffer per render thread: recording must not serialise the render it measures.
struct ray_recorder::per_thread {
  tbb::enumerable_thread_specific<recorded_rays> buffers;
};

ray_recorder::ray_recorder(const accelerator& inner)
    : inner_(inner), threads_(std::make_unique<per_thread>()) {}

ray_recorder::~ray_recorder() = default;

std::optional<hit> ray_recorder::intersect(const ray& r) const {
  threads_->buffers.local().intersect[size_t(r.kind)].push_back(r);
  return inner_.intersect(r);
}

bool ray_recorder::occluded(const ray& r) const {
  threads_->buffers.local().occluded[size_t(r.kind)].push_back(r);
  return inner_.occluded(r);
}

void ray_recorder::occluded_batch(const ray* rays, size_t count, uint8_t* blocked) const {
  recorded_rays& local = threads_->buffers.local();
  for (size_t i = 0; i < count; ++i) local.occluded[size_t(rays[i].kind)].push_back(rays[i]);
  inner_.occluded_batch(rays, count, blocked);
}

recorded_rays ray_recorder::rays() const {
  recorded_rays all;
  for (const recorded_rays& part : threads_->buffers)
    for (size_t k = 0; k < ray_kind_count; ++k) {
      all.intersect[k].insert(all.intersect[k].end(), part.intersect[k].begin(), part.intersect[k].end());
      all.occluded[k].insert(all.occluded[k].end(), part.occluded[k].begin(), part.occluded[k].end());
    }
  return all;
}

}  // namespace kiln
