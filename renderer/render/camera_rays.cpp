#include "render/camera_rays.h"

#include <algorithm>

#include "render/sample_pattern.h"
#include "render/tile_renderer.h"

namespace kiln {

namespace {

int samples_per_pixel(const render_settings& settings) { return std::max(settings.samples_per_pixel, 1); }

// The tile sample index of sample s of pixel (x, y): pixels row by row, each pixel's samples in order.
size_t tile_sample_index(const camera_ray_batch& b, int x, int y, int s, int spp) {
  const size_t pixel = size_t(y - b.y0) * size_t(b.x1 - b.x0) + size_t(x - b.x0);
  return pixel * size_t(spp) + size_t(s);
}

// The run of samples [begin, end) that starts at `begin`, and whether it is whole rows.
struct sample_run {
  size_t begin = 0, end = 0;
  bool whole_rows = false;
};

sample_run run_from(const camera_ray_batch& b, size_t begin, int spp) {
  const size_t per_row = size_t(b.x1 - b.x0) * size_t(spp);
  const size_t total = per_row * size_t(b.y1 - b.y0);
  if (per_row > camera_ray_batch::max_rays)
    return {begin, std::min(total, begin + camera_ray_batch::max_rays), false};
  const size_t row = begin / per_row;  // a run of rows starts at a row's first sample
  const size_t rows = std::max<size_t>(1, camera_ray_batch::max_rays / per_row);
  return {row * per_row, std::min(total, (row + rows) * per_row), true};
}

// Makes the camera rays of samples [run.begin, run.end), each with where it comes from.
void make_camera_rays(camera_ray_batch& b, const sample_run& run, const view_camera& cam,
                      const render_settings& settings) {
  const int spp = samples_per_pixel(settings);
  const size_t width = size_t(b.x1 - b.x0);
  const ray_cone cone = sample_cone(cam, spp);
  b.first = run.begin;
  b.rays.clear();
  b.sources.clear();
  // Each ray and its source are filled in place: built on the stack and then copied in whole,
  // the copy's wide loads stalled on the field-by-field stores just made.
  for (size_t i = run.begin; i < run.end; ++i) {
    camera_ray_source& src = b.sources.emplace_back();
    const size_t pixel = i / size_t(spp);
    src.x = b.x0 + int(pixel % width);
    src.y = b.y0 + int(pixel / width);
    src.sample = uint32_t(i % size_t(spp));
    src.offset = pixel_sample_offset(settings.random_samples, uint32_t(src.x), uint32_t(src.y), src.sample,
                                     uint32_t(spp));
    src.cone = cone;
    const float time = settings.motion_blur ? sample_time(settings.random_samples, uint32_t(src.x),
                                                          uint32_t(src.y), src.sample, uint32_t(spp))
                                            : 0.0f;
    const double px = src.x + double(src.offset.x), py = src.y + double(src.offset.y);
    ray& r = b.rays.emplace_back();
    if (settings.motion_blur && settings.camera_steps)
      generate_camera_ray(view_at_time(*settings.camera_steps, time), px, py, r);
    else
      generate_camera_ray(cam, px, py, r);
    r.time = time;
  }
}

// The closest hit of every ray of b: runs of whole rows as one coherent stream with packets, the
// others one ray at a time.
void trace_camera_rays(camera_ray_batch& b, bool coherent, const accelerator& accel) {
  b.hits.resize(b.rays.size());
  if (coherent) return accel.intersect_coherent(b.rays.data(), b.rays.size(), b.hits.data());
  for (size_t i = 0; i < b.rays.size(); ++i) b.hits[i] = accel.intersect(b.rays[i]);
}

}  // namespace

camera_ray_batch tile_camera_rays(int x0, int y0, int x1, int y1) {
  camera_ray_batch b;
  b.x0 = x0;
  b.y0 = y0;
  b.x1 = x1;
  b.y1 = y1;
  return b;
}

size_t camera_ray_at(camera_ray_batch& b, int x, int y, int s, const view_camera& cam,
                     const render_settings& settings, const accelerator& accel) {
  const int spp = samples_per_pixel(settings);
  const size_t index = tile_sample_index(b, x, y, s, spp);
  if (index < b.first || index >= b.first + b.rays.size()) {
    const sample_run run = run_from(b, index, spp);
    make_camera_rays(b, run, cam, settings);
    trace_camera_rays(b, settings.packets && run.whole_rows, accel);
  }
  return index - b.first;
}

}  // namespace kiln
