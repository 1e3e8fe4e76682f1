#include "render/frame_bands.h"

#include <cstdint>

namespace kiln {

pixel_rect frame_band(int index, int count, int width, int height) {
  // 64-bit products: index·height overflows int for large frames split many ways.
  auto row = [&](int k) { return int(int64_t(k) * height / count); };
  return pixel_rect{0, row(index), width, row(index + 1)};
}

}  // namespace kiln
