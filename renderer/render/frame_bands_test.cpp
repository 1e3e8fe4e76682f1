#include "render/frame_bands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace kiln {
namespace {

TEST(frame_bands, bands_tile_the_frame_rows_exactly_once) {
  for (int height : {1, 2, 7, 48, 480, 1001})
    for (int count = 1; count <= height && count <= 64; ++count) {
      std::vector<int> covered(size_t(height), 0);
      int smallest = height, largest = 0;
      for (int i = 0; i < count; ++i) {
        const pixel_rect band = frame_band(i, count, 13, height);
        EXPECT_EQ(band.x0, 0);
        EXPECT_EQ(band.x1, 13);
        ASSERT_GE(band.y0, 0);
        ASSERT_LE(band.y1, height);
        EXPECT_GE(band.height(), 1) << height << " rows, band " << i << "/" << count;
        for (int y = band.y0; y < band.y1; ++y) ++covered[size_t(y)];
        smallest = std::min(smallest, band.height());
        largest = std::max(largest, band.height());
      }
      for (int y = 0; y < height; ++y)
        ASSERT_EQ(covered[size_t(y)], 1) << "row " << y << ", " << count << " bands";
      EXPECT_LE(largest - smallest, 1) << height << " rows in " << count << " bands";
    }
}

TEST(frame_bands, consecutive_bands_meet) {
  for (int i = 0; i + 1 < 3; ++i) EXPECT_EQ(frame_band(i, 3, 64, 48).y1, frame_band(i + 1, 3, 64, 48).y0);
  EXPECT_EQ(frame_band(0, 3, 64, 48), (pixel_rect{0, 0, 64, 16}));
  EXPECT_EQ(frame_band(2, 3, 64, 48), (pixel_rect{0, 32, 64, 48}));
  EXPECT_EQ(frame_band(1, 3, 5, 10), (pixel_rect{0, 3, 5, 6}));  // 3, 3, 4 rows
}

TEST(frame_bands, large_frames_do_not_overflow) {
  EXPECT_EQ(frame_band(65535, 65536, 1, 65536), (pixel_rect{0, 65535, 1, 65536}));
}

}  // namespace
}  // namespace kiln
