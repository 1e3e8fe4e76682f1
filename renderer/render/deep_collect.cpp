#include "render/deep_collect.h"

#include <cstring>

namespace kiln {

void add_deep_surfaces(const scene& world, const matte_ids& mattes, depth_mode depth, const camera_sample& s,
                       float w, deep_collector& pixel) {
  pixel.weight += w;
  if (w == 0.0f) return;
  const float to_z = depth == depth_mode::planar ? s.view_cosine : 1.0f;
  for (const path_surface& surface : pixel.path) {
    const instance& inst = world.instances[surface.instance];
    deep_sample d;
    d.rgba = w * vec4(surface.radiance, surface.coverage);
    d.z = d.z_back = surface.distance * to_z;
    d.object = float(int32_t(inst.node));
    d.material = float(world.materials[inst.material].source_index);
    d.instance = float(surface.instance);
    const uint32_t crypto = matte_id(mattes.object_by_node, int32_t(inst.node));
    std::memcpy(&d.crypto_object, &crypto, sizeof crypto);
    pixel.samples.push_back(d);
  }
}

void finish_deep_pixel(deep_collector& pixel, deep_tile& tile) {
  if (pixel.weight > 0.0f) {
    for (deep_sample& d : pixel.samples) d.rgba /= pixel.weight;
    merge_deep_samples(pixel.samples);
    to_over_form(pixel.samples);
    tile.tidy = tile.tidy && deep_samples_tidy(pixel.samples);
    tile.samples.insert(tile.samples.end(), pixel.samples.begin(), pixel.samples.end());
  }
  tile.first.push_back(uint32_t(tile.samples.size()));
  pixel.samples.clear();
  pixel.weight = 0.0f;
}

}  // namespace kiln
