#include "shade/environment.h"

#include <algorithm>
#include <cmath>

#include "shade/texture_sampling.h"

namespace kiln {

vec2 environment_uv(const vec3& direction, float rotation_radians) {
  const vec3 d = glm::normalize(direction);
  const float phi = std::atan2(d.x, -d.z) - rotation_radians;  // 0 along -Z
  const float u = 0.5f + phi / (2.0f * pi);
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / pi;
  return {u - std::floor(u), v};
}

vec3 environment_radiance(const scene& s, const vec3& direction) {
  if (!s.env.has_map()) return s.env.color;
  return environment_radiance_at(s, environment_uv(direction, s.env.rotation));
}

vec3 environment_radiance_at(const scene& s, const vec2& uv) {
  const environment& env = s.env;
  if (!env.has_map()) return env.color;
  texture map;
  map.image = uint32_t(env.map_image);
  map.sampling = {wrap_mode::repeat, wrap_mode::clamp_to_edge, filter_mode::linear};
  return vec3(sample_texture(s, map, uv, texel_encoding::linear)) * env.intensity;
}

void prefetch_environment_radiance(const scene& s, const vec2& uv) {
  if (!s.env.has_map()) return;
  const image& im = s.images[size_t(s.env.map_image)];
  if (im.width <= 0 || im.height <= 0) return;
  const int x = std::clamp(int(uv.x * float(im.width)), 0, im.width - 1);
  const int y = std::clamp(int(uv.y * float(im.height)), 0, im.height - 1);
  for (int row : {std::max(y - 1, 0), y, std::min(y + 1, im.height - 1)}) {
    const size_t texel = (size_t(row) * size_t(im.width) + size_t(x)) * 4;
    if (!im.texels32.empty())
      __builtin_prefetch(&im.texels32[texel]);
    else if (!im.texels8.empty())
      __builtin_prefetch(&im.texels8[texel]);
  }
}

}  // namespace kiln
