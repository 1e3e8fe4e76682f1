// Punctual light evaluation (KHR_lights_punctual): direction to the light, distance, and the
// irradiance it delivers to a surface facing it, with inverse-square falloff, the recommended
// range window and the spot cone's smooth falloff. Depends on scene only.
#pragma once

#include "scene/scene.h"

namespace kiln {

struct light_sample {
  vec3 direction{0.0f};   // unit, from the shading point toward the light
  float distance = inf;   // to the light; infinite for directional lights
  vec3 irradiance{0.0f};  // W/m² (glTF units) on a surface perpendicular to direction
};

light_sample sample_light(const light& l, const vec3& point);

}  // namespace kiln
