// The film: one buffer per output, filled by the tile scheduler and read by io/exr.
// Depends on core only. Colour is premultiplied linear Rec.709 RGBA. Only the AOVs asked for have
// buffers; the others stay empty. Colour always has one: the renderer resolves into it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "render/aov_table.h"

namespace kiln {

// A rectangle of pixels, half-open: [x0, x1) × [y0, y1).
struct pixel_rect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  bool operator==(const pixel_rect& o) const { return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1; }
};

// One Cryptomatte rank: an id (the bits of the float the file stores) and the share of the pixel's
// filter weight whose samples hit it. Coverage 0 marks an unused rank (its id is then 0).
struct id_coverage {
  uint32_t id = 0;
  float coverage = 0.0f;
  bool operator==(const id_coverage& o) const { return id == o.id && coverage == o.coverage; }
};

struct film {
  int width = 0;  // of the stored region (the EXR data window)
  int height = 0;
  // Where the stored region sits in the full frame (the EXR display window), for crops.
  int x0 = 0, y0 = 0;
  int full_width = 0, full_height = 0;
  std::vector<vec4> color;   // premultiplied RGBA, row 0 at the top
  std::vector<float> depth;  // ray distance of the nearest sample; +inf where nothing was hit
  // The AOVs of three floats a pixel (aov_shape::triple), by aov; empty unless asked for. The nearest
  // sample's (N: world shading normal, P: world hit point, albedo: base colour; 0 for background)
  // or filtered like the beauty (the light split, direct, reflection, refraction; the camera
  // path's passes, shade/path_record.h's camera_passes). See vec3_layer.
  std::vector<vec3> vec3_layers[aov_count];
  // The nearest sample's TEXCOORD_0; 0 for background.
  std::vector<vec2> uv;
  // The nearest sample's glTF node, material and scene instance as exact integers; -1 for background.
  std::vector<glm::ivec3> ids;
  // The nearest sample's motion in pixels (u right, v up): (forward.u, forward.v) to the next
  // frame, (backward.u, backward.v) to the previous one; 0 for background.
  std::vector<vec4> motion;
  // Light groups (render/light_groups.h): their EXR layer names, and per pixel one premultiplied
  // colour per group, filtered like the beauty; empty unless asked for.
  // Kept when light groups or shadow mattes are asked for (the mattes are named after the lights).
  std::vector<std::string> light_group_layers;
  std::vector<vec3> light_groups;
  // The shadow mattes, filtered like the beauty: shadow_count() per pixel; empty unless asked for.
  std::vector<float> shadow;
  // Cryptomatte: aovs.crypto_depth ranks a pixel, coverage descending; empty unless asked for.
  std::vector<id_coverage> crypto_object;
  std::vector<id_coverage> crypto_material;
  aov_set aovs;  // what the file should hold

  film() = default;
  // group_layers: the light groups' layers (kept when a.has(aov::light_groups) or a.has(aov::shadow)).
  film(int w, int h, const aov_set& a = aov_set{}, const std::vector<std::string>& group_layers = {})
      : width(w), height(h), full_width(w), full_height(h), aovs(a) {
    const size_t n = size_t(w) * h;
    color.assign(n, vec4(0.0f));
    if (a.has(aov::depth)) depth.assign(n, inf);
    for (const aov_row& row : aov_table)
      if (row.shape == aov_shape::triple && a.has(row.id)) vec3_layers[int(row.id)].assign(n, vec3(0.0f));
    if (a.has(aov::uv)) uv.assign(n, vec2(0.0f));
    if (a.has(aov::ids)) ids.assign(n, glm::ivec3(-1));
    if (a.has(aov::motion)) motion.assign(n, vec4(0.0f));
    if (a.has(aov::light_groups) || a.has(aov::shadow)) light_group_layers = group_layers;
    if (a.has(aov::light_groups)) light_groups.assign(n * group_layers.size(), vec3(0.0f));
    if (a.has(aov::shadow)) shadow.assign(n * size_t(shadow_count()), 0.0f);
    if (a.has(aov::crypto_object)) crypto_object.assign(n * size_t(a.crypto_depth), id_coverage{});
    if (a.has(aov::crypto_material)) crypto_material.assign(n * size_t(a.crypto_depth), id_coverage{});
  }

  size_t index(int x, int y) const { return size_t(y) * width + x; }
  // The buffer of an AOV of three floats a pixel (empty unless asked for).
  std::vector<vec3>& vec3_layer(aov a) { return vec3_layers[int(a)]; }
  const std::vector<vec3>& vec3_layer(aov a) const { return vec3_layers[int(a)]; }
  int light_group_count() const { return int(light_group_layers.size()); }
  // The punctual lights: every group but emission and environment.
  int light_count() const { return std::max(light_group_count() - 2, 0); }
  // The shadow mattes: one per punctual light, then the environment's (every group but emission).
  int shadow_count() const { return std::max(light_group_count() - 1, 0); }
  // The shadow matte layer i: "shadow_" + its group's name ("lightgroup_<name>"): light i's, and
  // after the lights the environment's.
  std::string shadow_layer(int i) const {
    const int lights = light_count();
    const std::string& group = light_group_layers[size_t(i < lights ? i : lights + 1)];
    const size_t prefix = group.find('_');
    return "shadow" + (prefix == std::string::npos ? "_" + group : group.substr(prefix));
  }
};

// The bytes a w × h film with aovs (and light_groups groups) holds: its constructor's buffers.
inline uint64_t film_bytes(int w, int h, const aov_set& a, int light_groups = 0) {
  uint64_t per_pixel = sizeof(vec4);
  per_pixel += a.has(aov::depth) ? sizeof(float) : 0;
  for (const aov_row& row : aov_table)
    per_pixel += row.shape == aov_shape::triple && a.has(row.id) ? sizeof(vec3) : 0;
  per_pixel += a.has(aov::light_groups) ? sizeof(vec3) * uint64_t(light_groups) : 0;
  per_pixel += a.has(aov::shadow) ? sizeof(float) * uint64_t(std::max(light_groups - 1, 0)) : 0;
  per_pixel += a.has(aov::uv) ? sizeof(vec2) : 0;
  per_pixel += a.has(aov::ids) ? sizeof(glm::ivec3) : 0;
  per_pixel += a.has(aov::motion) ? sizeof(vec4) : 0;
  for (bool crypto : {a.has(aov::crypto_object), a.has(aov::crypto_material)})
    per_pixel += crypto ? sizeof(id_coverage) * uint64_t(a.crypto_depth) : 0;
  return per_pixel * uint64_t(w) * uint64_t(h);
}

}  // namespace kiln
