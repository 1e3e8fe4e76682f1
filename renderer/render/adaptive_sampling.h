// Whitted's adaptive supersampling (Whitted 1980, "An improved illumination model for shaded
// display", section 4): a pixel is first sampled at its four corners; where the corners differ by
// more than a threshold the square is split into four and the new corners traced, recursively up
// to a depth limit; the pixel is the area-weighted mean of its squares' corner means. Sample
// positions depend only on the film position, so the image does not depend on scheduling.
// Depends on core and render only; the tracing is a callback.
#pragma once

#include <functional>
#include <vector>

#include "render/camera_sample.h"

namespace kiln {

struct adaptive_options {
  float threshold = 0.0f;  // split where a channel (R, G, B, A) spans more than this; 0 = off
  int max_depth = 2;       // splits per pixel at most: 2 means squares down to 1/4 pixel a side
  // Fill adaptive_pixel::corners (for Cryptomatte, the light split, the light groups and the
  // camera passes).
  bool collect_corners = false;
};

constexpr int max_adaptive_depth = 8;

// True when the four corner samples of a square call for a split: some channel of rgba spans
// more than threshold, or they did not all hit the same instance (or all miss).
bool corners_differ(const camera_sample& a, const camera_sample& b, const camera_sample& c,
                    const camera_sample& d, float threshold);

// Traces the sample at film position (x, y) in pixels; must be a pure function of the position.
using sample_tracer = std::function<camera_sample(double x, double y)>;

// A corner of a final square and its weight in the pixel's mean.
struct weighted_corner {
  float weight = 0.0f;       // 1/4 of its square's area: the pixel's weights sum to exactly 1
  std::vector<vec3> groups;  // its colour by light group (empty unless the samples carry them)
  camera_passes passes;      // its light split and other passes (zero unless the samples carry them)
  // The instances it covers (none for a miss or a sample with non-finite radiance).
  path_layer layers[max_path_layers];
  int layer_count = 0;
};

// What a refined pixel contributes to the film.
struct adaptive_pixel {
  vec4 rgba{0.0f};        // area-weighted mean of the squares' corner means
  camera_sample nearest;  // the nearest sample the pixel used: its depth, normal and other AOVs
  // With collect_corners: the corners of each final square.
  std::vector<weighted_corner> corners;
};

// Per-thread scratch: the samples already traced inside the current pixel, on its finest grid,
// so squares that share a corner trace it once.
struct adaptive_scratch {
  std::vector<camera_sample> grid;
  std::vector<bool> known;
  std::vector<size_t> touched;
};

// Refines pixel (x, y) whose corners (top-left, top-right, bottom-left, bottom-right) are given;
// new samples come from trace. Corners on the pixel's border are recomputed by the neighbour
// that needs them, so the result is a function of the pixel alone.
adaptive_pixel refine_pixel(int x, int y, const camera_sample corners[4], const adaptive_options& options,
                            const sample_tracer& trace, adaptive_scratch& scratch);

}  // namespace kiln
