// Camera rays as the first stage of a tile's render: the rays of a run of the tile's samples are
// made first, in the order the pixels are shaded (rows top to bottom, pixels left to right, each
// pixel's samples in order), then traced to their closest hits (one ray at a time, or each pixel's
// samples together as Embree packets through accelerator::intersect_coherent), and shading starts
// from each stored hit. A packet's traversal may break a tie between two coincident surfaces
// otherwise than a single ray does; since a packet holds one pixel's samples only, that choice is
// the pixel's own and does not change with the tile size, crop or region.
// Depends on render and the accelerator interface; never on a backend.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "accel/accelerator.h"
#include "render/view_camera.h"
#include "shade/ray_cone.h"

namespace kiln {

struct render_settings;

// Where a camera ray comes from.
struct camera_ray_source {
  int x = 0, y = 0;     // the pixel, in frame pixels
  uint32_t sample = 0;  // its index among the pixel's samples (what seeds its position)
  vec2 offset{0.0f};    // the film position inside the pixel, in [0, 1)²: the filter weighs it
  ray_cone cone;        // the ray's footprint at the camera
  float time = 0.0f;    // the sample's time in the shutter; 0 until motion blur
};

// The camera rays of one run of a tile's samples, with their closest hits, index by index.
struct camera_ray_batch {
  // At most this many rays a batch (one 32×32 tile at 1 spp): their queries stay in cache.
  static constexpr size_t max_rays = 1024;

  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the tile, in frame pixels
  size_t first = 0;                    // the tile sample index of rays[0]
  std::vector<ray> rays;
  std::vector<camera_ray_source> sources;
  std::vector<std::optional<hit>> hits;
};

// An empty batch for the tile [x0, x1) × [y0, y1).
camera_ray_batch tile_camera_rays(int x0, int y0, int x1, int y1);

// The position in b of sample s of pixel (x, y) of its tile, after making and tracing the run of
// samples that holds it when b does not: whole pixel rows, as many as fit in max_rays; else whole
// pixels from (x, y) on; else max_rays of the pixel's samples, counted from its first. The image
// does not depend on the order pixels are asked for.
size_t camera_ray_at(camera_ray_batch& b, int x, int y, int s, const view_camera& cam,
                     const render_settings& settings, const accelerator& accel);

}  // namespace kiln
