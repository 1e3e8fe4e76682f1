// Camera rays traced together: before a run of a tile's pixel rows is shaded, their camera rays
// are generated in the order the pixels will ask for them and handed to the backend at once
// (accelerator::intersect_coherent: Embree traces them as coherent packets). Shading then sees an
// accelerator that answers each of those rays from the batch and forwards every other query, so
// camera_sample and shading stay single-ray code and the image is what single rays give: a ray is
// answered from the batch only when it equals, bit for bit, the next batched ray.
// Depends on render and the accelerator interface; never on a backend.
#pragma once

#include <vector>

#include "accel/accelerator.h"
#include "render/view_camera.h"
#include "shade/whitted.h"

namespace kiln {

struct render_settings;

class primary_ray_batch final : public accelerator {
 public:
  // At most this many camera rays per batch (one 32×32 tile at 1 spp): their queries stay in cache.
  static constexpr size_t max_rays = 1024;

  explicit primary_ray_batch(const accelerator& inner) : inner_(inner) {}

  // Traces the camera rays of rows [y, y_end) of pixels [x0, x1), where y_end is as many rows as fit
  // in max_rays (at least one) but not past y1, and returns y_end. With more than max_rays samples
  // in one row it batches nothing and returns y1: every ray then goes to the backend alone.
  int prepare(const view_camera& cam, const render_settings& settings, int x0, int x1, int y, int y1);

  std::optional<hit> intersect(const ray& r) const override;
  bool occluded(const ray& r) const override { return inner_.occluded(r); }
  void throw_if_failed() const override { inner_.throw_if_failed(); }

 private:
  const accelerator& inner_;
  std::vector<ray> rays_;
  std::vector<std::optional<hit>> hits_;
  mutable size_t next_ = 0;  // one batch serves one thread, in order
};

// ctx answering queries through accel instead of its own accelerator (copies every other field of
// shading_context; keep in step when one is added).
inline shading_context with_accelerator(const shading_context& ctx, const accelerator& accel) {
  shading_context out{ctx.world, accel, ctx.options};
  out.see_through_shadows = ctx.see_through_shadows;
  out.textures = ctx.textures;
  out.cancel = ctx.cancel;
  return out;
}

}  // namespace kiln
