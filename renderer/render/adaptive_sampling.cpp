#include "render/adaptive_sampling.h"

#include <algorithm>
#include <cmath>

namespace kiln {

bool corners_differ(const camera_sample& a, const camera_sample& b, const camera_sample& c,
                    const camera_sample& d, float threshold) {
  if (a.instance != b.instance || a.instance != c.instance || a.instance != d.instance) return true;
  for (int k = 0; k < 4; ++k) {
    float lo = std::min(std::min(a.rgba[k], b.rgba[k]), std::min(c.rgba[k], d.rgba[k]));
    float hi = std::max(std::max(a.rgba[k], b.rgba[k]), std::max(c.rgba[k], d.rgba[k]));
    if (hi - lo > threshold) return true;
  }
  return false;
}

namespace {

struct pixel_refiner {
  int x, y;
  int side;  // grid points per side: 2^max_depth + 1
  double step;
  const adaptive_options& options;
  const sample_tracer& trace;
  adaptive_scratch& scratch;
  adaptive_pixel result;

  void note(const camera_sample& s) {
    if (s.depth < result.nearest.depth) keep_as_nearest(s, result.nearest);
  }

  void store(int i, int j, const camera_sample& s) {
    size_t k = size_t(j) * side + i;
    scratch.grid[k] = s;
    scratch.known[k] = true;
    scratch.touched.push_back(k);
    note(s);
  }

  const camera_sample& at(int i, int j) {
    size_t k = size_t(j) * side + i;
    if (!scratch.known[k]) store(i, j, trace(x + i * step, y + j * step));
    return scratch.grid[k];
  }

  // Mean over the square with top-left grid point (i, j), `size` grid steps a side.
  vec4 square(int i, int j, int size, int level) {
    const camera_sample &a = at(i, j), &b = at(i + size, j), &c = at(i, j + size),
                        &d = at(i + size, j + size);
    if (level < options.max_depth && corners_differ(a, b, c, d, options.threshold)) {
      const int h = size / 2;
      vec4 q0 = square(i, j, h, level + 1);
      vec4 q1 = square(i + h, j, h, level + 1);
      vec4 q2 = square(i, j + h, h, level + 1);
      vec4 q3 = square(i + h, j + h, h, level + 1);
      return 0.25f * (q0 + q1 + q2 + q3);
    }
    if (options.collect_corners) {
      // Squares at level L cover 4^-L of the pixel; powers of two, so the weights are exact.
      const float w = std::ldexp(0.25f, -2 * level);
      for (const camera_sample* s : {&a, &b, &c, &d}) {
        weighted_corner corner;
        corner.weight = w;
        corner.groups = s->groups;
        corner.passes = s->passes;
        if (s->finite) {
          std::copy(s->layers, s->layers + s->layer_count, corner.layers);
          corner.layer_count = s->layer_count;
        }
        result.corners.push_back(corner);
      }
    }
    return 0.25f * (a.rgba + b.rgba + c.rgba + d.rgba);
  }
};

}  // namespace

adaptive_pixel refine_pixel(int x, int y, const camera_sample corners[4], const adaptive_options& options,
                            const sample_tracer& trace, adaptive_scratch& scratch) {
  const int depth = std::clamp(options.max_depth, 0, max_adaptive_depth);
  const int cells = 1 << depth;
  const int side = cells + 1;
  const size_t points = size_t(side) * side;
  if (scratch.grid.size() < points) {
    scratch.grid.resize(points);
    scratch.known.assign(points, false);
  }
  adaptive_options clamped = options;
  clamped.max_depth = depth;
  pixel_refiner r{x, y, side, 1.0 / cells, clamped, trace, scratch, {}};
  r.store(0, 0, corners[0]);
  r.store(cells, 0, corners[1]);
  r.store(0, cells, corners[2]);
  r.store(cells, cells, corners[3]);
  r.result.rgba = r.square(0, 0, cells, 0);
  for (size_t k : scratch.touched) scratch.known[k] = false;
  scratch.touched.clear();
  return r.result;
}

}  // namespace kiln
