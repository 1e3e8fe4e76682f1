// The film: one buffer per output, filled by the tile scheduler and read by io/exr.
// Depends on core only. Colour is premultiplied linear Rec.709 RGBA. Only the AOVs asked for have
// buffers; the others stay empty. Colour always has one: the renderer resolves into it.
#pragma once

#include "core/math.h"
#include "render/aov_list.h"

#include <vector>

namespace kiln {

struct film {
  int width = 0;
  int height = 0;
  std::vector<vec4> color;   // premultiplied RGBA, row 0 at the top
  std::vector<float> depth;  // ray distance of the nearest sample; +inf where nothing was hit
  std::vector<vec3> normal;  // world shading normal of the nearest sample; 0 for background
  // The nearest sample's world hit point, base colour and TEXCOORD_0; 0 for background.
  std::vector<vec3> position;
  std::vector<vec3> albedo;
  std::vector<vec2> uv;
  // The nearest sample's glTF node, material and scene instance as exact integers; -1 for background.
  std::vector<glm::ivec3> ids;
  aov_set aovs;  // what the file should hold

  film() = default;
  film(int w, int h, const aov_set& a = aov_set{}) : width(w), height(h), aovs(a) {
    const size_t n = size_t(w) * h;
    color.assign(n, vec4(0.0f));
    if (a.depth) depth.assign(n, inf);
    if (a.normal) normal.assign(n, vec3(0.0f));
    if (a.position) position.assign(n, vec3(0.0f));
    if (a.albedo) albedo.assign(n, vec3(0.0f));
    if (a.uv) uv.assign(n, vec2(0.0f));
    if (a.ids) ids.assign(n, glm::ivec3(-1));
  }

  size_t index(int x, int y) const { return size_t(y) * width + x; }
};

}  // namespace kiln
