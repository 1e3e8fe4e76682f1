#include "io/exr/preview_codes.h"

#include <algorithm>
#include <cctype>
#include <cmath>

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

}  // namespace kiln
