// Which output layer (AOV): one name per layer, in the order kiln/aovs lists them. The AOV table
// (render/aov_table.h), the set a render asks for (render/aov_list.h) and the passes shading files
// per sample (shade/path_record.h) are all indexed by it, so shading can name the layer it records
// without seeing the table. Names only; depends on nothing.
#pragma once

#include <cstdint>

namespace kiln {

// A new AOV goes at the end: the order is the files' layer order, and every AOV from direct on is
// a slot of shade/path_record.h's camera_passes.
enum class aov : uint8_t {
  beauty,
  depth,
  normal,
  position,
  albedo,
  uv,
  ids,
  motion,
  crypto_object,
  crypto_material,
  direct,
  reflection,
  refraction,
  light_groups,
  albedo_filtered,
  normal_filtered,
  diffuse,
  specular,
  shadow,
  emission,
};
constexpr int aov_count = int(aov::emission) + 1;

}  // namespace kiln
