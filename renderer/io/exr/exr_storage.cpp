#include "io/exr/exr_storage.h"

#include <algorithm>

namespace kiln {

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
