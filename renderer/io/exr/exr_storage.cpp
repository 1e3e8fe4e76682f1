#include "io/exr/exr_storage.h"

#include <algorithm>

#include "io/exr/cryptomatte.h"

namespace kiln {

const std::vector<std::string>& exr_part_names() {
  static const std::vector<std::string> names = {"rgba",
                                                 "depth",
                                                 "N",
                                                 "P",
                                                 "albedo",
                                                 "uv",
                                                 "id",
                                                 "forward",
                                                 "backward",
                                                 "direct",
                                                 "reflection",
                                                 "refraction",
                                                 "albedo_filtered",
                                                 "N_filtered",
                                                 "diffuse",
                                                 "specular",
                                                 crypto_object_layer_name,
                                                 crypto_material_layer_name};
  return names;
}

const std::string& exr_part_name(exr_part part) { return exr_part_names()[size_t(part)]; }

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
