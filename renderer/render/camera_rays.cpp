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

// The run of samples [begin, end) that holds sample `index`.
struct sample_run {
  size_t begin = 0, end = 0;
};

// Whole rows of the tile, as many as fit in max_rays; else whole pixels from index's pixel on, as
// many as fit; else (a pixel of more than max_rays samples) max_rays of index's pixel's samples,
// counted from its first. Either way a run holds a pixel's samples from its first or from a multiple
// of max_rays, so the packets of trace_camera_rays depend on the pixel alone.
sample_run run_from(const camera_ray_batch& b, size_t index, int spp) {
  const size_t per_row = size_t(b.x1 - b.x0) * size_t(spp);
  const size_t total = per_row * size_t(b.y1 - b.y0);
  const size_t max_rays = camera_ray_batch::max_rays;
  if (per_row <= max_rays) {
    const size_t row = index / per_row;
    return {row * per_row, std::min(total, (row + max_rays / per_row) * per_row)};
  }
  const size_t pixel_first = index - index % size_t(spp);
  if (size_t(spp) <= max_rays)
    return {pixel_first, std::min(total, pixel_first + max_rays / size_t(spp) * size_t(spp))};
  const size_t begin = index - (index - pixel_first) % max_rays;
  return {begin, std::min(pixel_first + size_t(spp), begin + max_rays)};
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

// The closest hit of every ray of b: one ray at a time, or with packets each pixel's samples of the
// run together (accelerator::intersect_coherent: Embree's packets, filled from the pixel's first
// sample in the run). A packet's traversal may break a tie between coincident surfaces otherwise
// than a single ray; packets of one pixel's samples alone make that choice the pixel's own, the
// same whatever tile size, crop or region renders it. A pixel of one sample is one ray.
void trace_camera_rays(camera_ray_batch& b, bool packets, const accelerator& accel) {
  const size_t n = b.rays.size();
  b.hits.resize(n);
  if (!packets) {
    for (size_t i = 0; i < n; ++i) b.hits[i] = accel.intersect(b.rays[i]);
    return;
  }
  for (size_t begin = 0, end = 0; begin < n; begin = end) {
    const camera_ray_source& first = b.sources[begin];
    for (end = begin + 1; end < n && b.sources[end].x == first.x && b.sources[end].y == first.y;) ++end;
    if (end - begin == 1)
      b.hits[begin] = accel.intersect(b.rays[begin]);
    else
      accel.intersect_coherent(&b.rays[begin], end - begin, &b.hits[begin]);
  }
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
    trace_camera_rays(b, settings.packets, accel);
  }
  return index - b.first;
}

}  // namespace kiln
