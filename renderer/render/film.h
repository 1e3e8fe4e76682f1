// The film: one buffer per output, filled by the tile scheduler and read by io/exr.
// Depends on core only. Colour is premultiplied linear Rec.709 RGBA.
#pragma once

#include "core/math.h"

#include <vector>

namespace kiln {

struct film {
  int width = 0;
  int height = 0;
  std::vector<vec4> color;   // premultiplied RGBA, row 0 at the top
  std::vector<float> depth;  // ray distance of the nearest sample; +inf where nothing was hit
  std::vector<vec3> normal;  // world shading normal of the nearest sample; 0 for background

  film() = default;
  film(int w, int h)
      : width(w), height(h), color(size_t(w) * h, vec4(0.0f)), depth(size_t(w) * h, inf),
        normal(size_t(w) * h, vec3(0.0f)) {}

  size_t index(int x, int y) const { return size_t(y) * width + x; }
};

}  // namespace kiln
