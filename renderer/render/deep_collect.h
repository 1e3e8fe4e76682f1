// Collects one pixel's deep samples from its camera samples as the tile renderer shades them, and
// stores the finished pixel in its tile (render/deep_pixel.h). Depends on scene and render only.
#pragma once

#include <vector>

#include "render/camera_sample.h"
#include "render/deep_pixel.h"
#include "render/id_coverage.h"
#include "scene/scene.h"

namespace kiln {

// One pixel in progress: its camera samples' path surfaces, each weighted by its sample's filter
// weight, and the sum of those weights; path is the buffer each camera sample's surfaces go to
// (sample_outputs::surfaces).
struct deep_collector {
  std::vector<deep_sample> samples;
  float weight = 0.0f;
  std::vector<path_surface> path;
};

// Adds the surfaces in pixel.path of camera sample s (finite, with filter weight w for its own
// pixel) with their ids; depth as the Z AOV measures it.
void add_deep_surfaces(const scene& world, const matte_ids& mattes, depth_mode depth, const camera_sample& s,
                       float w, deep_collector& pixel);

// Divides the pixel's samples by its weight (so they sum to the flat pixel, Σ w·L / Σ w, as the
// splat film resolves it), merges, converts them to over-form and appends them to tile as its
// next pixel; then empties pixel for the next.
void finish_deep_pixel(deep_collector& pixel, deep_tile& tile);

}  // namespace kiln
