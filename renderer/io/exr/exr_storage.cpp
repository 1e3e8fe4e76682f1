#include "io/exr/exr_storage.h"

#include <algorithm>
#include <sstream>

#include "io/exr/cryptomatte.h"

namespace kiln {

const std::vector<std::string>& exr_part_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const aov_row& row : aov_table) {
      std::istringstream parts(row.parts);
      for (std::string part; parts >> part;) out.push_back(part);
    }
    out.push_back(crypto_object_layer_name);
    out.push_back(crypto_material_layer_name);
    return out;
  }();
  return names;
}

const std::vector<std::string>& exr_compression_names() {
  static const std::vector<std::string> names = {"none",  "rle", "zips", "zip",  "piz",
                                                 "pxr24", "b44", "b44a", "dwaa", "dwab"};
  return names;
}

bool is_lossy_compression(const std::string& name) {
  static const std::vector<std::string> lossy = {"pxr24", "b44", "b44a", "dwaa", "dwab"};
  return std::find(lossy.begin(), lossy.end(), name) != lossy.end();
}

bool compression_takes_level(const std::string& name) {
  return name == "zip" || name == "zips" || name == "dwaa" || name == "dwab";
}

}  // namespace kiln
