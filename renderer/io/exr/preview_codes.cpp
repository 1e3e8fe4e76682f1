#include "io/exr/preview_codes.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

namespace kiln {

std::string preview_format(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos) return {};
  std::string extension = path.substr(dot + 1);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (extension == "png") return "png";
  if (extension == "jpg" || extension == "jpeg") return "jpeg";
  return {};
}

unsigned char preview_code(float linear, double exposure) {
  double v = double(linear) * std::exp2(exposure);
  v = std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 1.0);
  const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
  return (unsigned char)std::lround(255.0 * encoded);
}

namespace {

float float_of(uint32_t bits) {
  float f = 0.0f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

}  // namespace

preview_code_table make_preview_code_table(double exposure) {
  preview_code_table table;
  constexpr uint32_t infinity = 0x7f800000u;  // positive floats order as their bits do
  for (int k = 1; k <= 255; ++k) {
    uint32_t below = 0, reaching = infinity;  // code(+0) = 0 < k <= 255 = code(+inf)
    while (reaching - below > 1) {
      const uint32_t middle = below + (reaching - below) / 2;
      (preview_code(float_of(middle), exposure) >= k ? reaching : below) = middle;
    }
    table.thresholds[size_t(k - 1)] = float_of(reaching);
  }
  const auto code_of = [&table](float value) {
    return uint8_t(std::upper_bound(table.thresholds.begin(), table.thresholds.end(), value) -
                   table.thresholds.begin());
  };
  table.first.resize(infinity >> 16);
  table.last.resize(infinity >> 16);
  for (uint32_t run = 0; run < (infinity >> 16); ++run) {
    table.first[run] = code_of(float_of(run << 16));
    table.last[run] = code_of(float_of((run << 16) | 0xFFFFu));
  }
  return table;
}

}  // namespace kiln
