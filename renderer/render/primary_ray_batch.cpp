#include "render/primary_ray_batch.h"

#include <cstring>

#include "render/sample_pattern.h"
#include "render/tile_renderer.h"

namespace kiln {

namespace {

bool same_bits(const ray& a, const ray& b) {
  return std::memcmp(&a.origin, &b.origin, sizeof(a.origin)) == 0 &&
         std::memcmp(&a.direction, &b.direction, sizeof(a.direction)) == 0 &&
         std::memcmp(&a.tmin, &b.tmin, sizeof(a.tmin)) == 0 &&
         std::memcmp(&a.tmax, &b.tmax, sizeof(a.tmax)) == 0;
}

}  // namespace

int primary_ray_batch::prepare(const view_camera& cam, const render_settings& settings, int x0, int x1, int y,
                               int y1) {
  rays_.clear();
  next_ = 0;
  const int spp = std::max(settings.samples_per_pixel, 1);
  const size_t per_row = size_t(x1 - x0) * size_t(spp);
  if (per_row == 0 || per_row > max_rays) return y1;
  const int y_end = std::min(y1, y + int(std::max<size_t>(1, max_rays / per_row)));
  // The pixel order and sample positions of render_pixel, which trace_camera_sample turns into
  // exactly these rays.
  for (int py = y; py < y_end; ++py)
    for (int px = x0; px < x1; ++px)
      for (int s = 0; s < spp; ++s) {
        const vec2 offset = pixel_sample_offset(settings.random_samples, uint32_t(px), uint32_t(py),
                                                uint32_t(s), uint32_t(spp));
        rays_.push_back(generate_camera_ray(cam, px + double(offset.x), py + double(offset.y)));
      }
  hits_.resize(rays_.size());
  inner_.intersect_coherent(rays_.data(), rays_.size(), hits_.data());
  return y_end;
}

std::optional<hit> primary_ray_batch::intersect(const ray& r) const {
  if (next_ < rays_.size() && same_bits(r, rays_[next_])) return hits_[next_++];
  return inner_.intersect(r);
}

}  // namespace kiln
