#include "shade/lights.h"

#include <algorithm>
#include <cmath>

namespace kiln {

namespace {

// KHR_lights_punctual's recommended range window, clamp(1 - (d/range)^4, 0, 1), applied on top of
// the inverse-square law: zero at the range, about 1 well inside it. (Some engines square the
// window; the specification's recommendation does not.)
float range_window(float distance, float range) {
  if (range <= 0.0f) return 1.0f;
  float ratio = distance / range;
  return std::clamp(1.0f - ratio * ratio * ratio * ratio, 0.0f, 1.0f);
}

// glTF's spot attenuation: smoothstep-like in cos angle between the inner and outer cones.
float spot_factor(const light& l, const vec3& to_point) {
  float cos_outer = std::cos(l.outer_cone_angle);
  float cos_inner = std::cos(l.inner_cone_angle);
  float scale = 1.0f / std::max(0.001f, cos_inner - cos_outer);
  float offset = -cos_outer * scale;
  float cd = glm::dot(l.direction, to_point);
  float attenuation = std::clamp(cd * scale + offset, 0.0f, 1.0f);
  return attenuation * attenuation;
}

}  // namespace

light_sample sample_light(const light& l, const vec3& point) {
  light_sample ls;
  vec3 radiant = l.color * l.intensity;
  if (l.kind == light_kind::directional) {
    ls.direction = -l.direction;
    ls.irradiance = radiant;
    return ls;
  }
  dvec3 offset = l.position - dvec3(point);
  double distance = glm::length(offset);
  if (!(distance > 0.0) || !std::isfinite(distance)) return ls;
  ls.direction = vec3(offset / distance);
  ls.distance = float(distance);
  float falloff = range_window(ls.distance, l.range) / float(distance * distance);
  if (l.kind == light_kind::spot) falloff *= spot_factor(l, -ls.direction);
  ls.irradiance = radiant * falloff;
  return ls;
}

}  // namespace kiln
