#include "io/exr/exr_stitch.h"

#include <algorithm>
#include <cstring>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/memory_budget.h"

namespace kiln {

namespace {

std::string describe(const pixel_rect& r) {
  return "[" + std::to_string(r.x0) + "," + std::to_string(r.x1) + ")x[" + std::to_string(r.y0) + "," +
         std::to_string(r.y1) + ")";
}

bool inside(const pixel_rect& r, const pixel_rect& frame) {
  return r.x0 >= frame.x0 && r.y0 >= frame.y0 && r.x1 <= frame.x1 && r.y1 <= frame.y1;
}

bool overlap(const pixel_rect& a, const pixel_rect& b) {
  return std::max(a.x0, b.x0) < std::min(a.x1, b.x1) && std::max(a.y0, b.y0) < std::min(a.y1, b.y1);
}

// Every region agrees with the first on frame and channels, lies in the frame and overlaps no other.
void check_regions(const std::vector<std::string>& paths, const std::vector<exr_image>& regions) {
  const exr_image& first = regions.front();
  for (size_t k = 0; k < regions.size(); ++k) {
    const exr_image& r = regions[k];
    if (!(r.display_window == first.display_window))
      throw input_error(
          paths[k], "displayWindow",
          describe(r.display_window) + " differs from " + describe(first.display_window) + " of " + paths[0]);
    if (r.channel_names != first.channel_names || r.channel_formats != first.channel_formats)
      throw input_error(paths[k], "channels", "channel names or formats differ from those of " + paths[0]);
    if (!inside(r.data_window, r.display_window))
      throw input_error(
          paths[k], "dataWindow",
          describe(r.data_window) + " reaches outside the display window " + describe(r.display_window));
    for (size_t j = 0; j < k; ++j)
      if (overlap(regions[j].data_window, r.data_window))
        throw input_error(
            paths[k], "dataWindow",
            describe(r.data_window) + " overlaps " + describe(regions[j].data_window) + " of " + paths[j]);
  }
}

// The first pixel of the frame no region holds, as "(x, y)"; empty when all are covered. The
// regions lie inside the frame without overlapping, so they cover it exactly when their areas add
// up to its area; otherwise the first gap lies on the frame's first row or on a row where a region
// starts or ends. No map of the frame is made: a 100000² frame's would take 10 GB.
std::string first_missing_pixel(const std::vector<exr_image>& regions, const pixel_rect& frame) {
  uint64_t area = 0;
  std::vector<int> rows = {frame.y0};
  for (const exr_image& r : regions) {
    area += uint64_t(r.data_window.width()) * uint64_t(r.data_window.height());
    rows.insert(rows.end(), {r.data_window.y0, r.data_window.y1});
  }
  if (area == uint64_t(frame.width()) * uint64_t(frame.height())) return {};
  std::sort(rows.begin(), rows.end());
  for (const int y : rows) {
    if (y >= frame.y1) break;
    std::vector<std::pair<int, int>> spans;  // [x0, x1) of the regions on row y
    for (const exr_image& r : regions)
      if (r.data_window.y0 <= y && y < r.data_window.y1)
        spans.emplace_back(r.data_window.x0, r.data_window.x1);
    std::sort(spans.begin(), spans.end());
    int x = frame.x0;
    for (const auto& [x0, x1] : spans) {
      if (x0 > x) break;
      x = x1;
    }
    if (x < frame.x1) return "(" + std::to_string(x) + ", " + std::to_string(y) + ")";
  }
  return {};
}

// The frame took as long as its regions together: renderTimeSeconds (and kiln/render_seconds) become
// their sum, and kiln/band_render_seconds (a float vector) keeps each region's own time, in input order. Left
// as the first region's header when some region records no time (not kiln's).
void record_region_times(const std::vector<exr_image>& regions, exr_image& frame) {
  double total = 0.0;
  std::vector<float> times;
  for (const exr_image& r : regions) {
    const std::optional<float> seconds = exr_float_attribute(r, "renderTimeSeconds");
    if (!seconds) return;
    total += double(*seconds);
    times.push_back(*seconds);
  }
  set_exr_attribute(frame, "renderTimeSeconds", float(total));
  set_exr_attribute(frame, "kiln/render_seconds", float(total));
  set_exr_attribute(frame, "kiln/band_render_seconds", times);
}

}  // namespace

exr_image stitch_regions(const std::vector<std::string>& paths, const std::vector<exr_image>& regions,
                         memory_budget* budget) {
  if (regions.empty() || paths.size() != regions.size()) throw input_error("", "stitch", "no input images");
  check_regions(paths, regions);
  const pixel_rect frame = regions.front().display_window;
  const std::string missing = first_missing_pixel(regions, frame);
  if (!missing.empty())
    throw input_error(paths.back(), "dataWindow",
                      "with this file the " + std::to_string(paths.size()) +
                          " inputs still do not cover the display window " + describe(frame) + ": pixel " +
                          missing + " is missing");
  exr_image out = regions.front();
  out.data_window = frame;
  const size_t pixel = out.pixel_bytes();
  const size_t frame_row = size_t(frame.width()) * pixel;
  if (budget)
    budget->charge(uint64_t(frame_row) * uint64_t(frame.height()), paths.front(),
                   "the stitched frame's pixels (display window " + describe(frame) + ", " +
                       std::to_string(pixel) + " bytes each)");
  out.pixels.assign(frame_row * size_t(frame.height()), 0);
  for (const exr_image& r : regions) {
    const size_t row = size_t(r.data_window.width()) * pixel;
    for (int y = r.data_window.y0; y < r.data_window.y1; ++y)
      std::memcpy(
          out.pixels.data() + size_t(y - frame.y0) * frame_row + size_t(r.data_window.x0 - frame.x0) * pixel,
          r.pixels.data() + size_t(y - r.data_window.y0) * row, row);
  }
  record_region_times(regions, out);
  return out;
}

}  // namespace kiln
