// The perfectly specular parts of a glTF material's BSDF at a shading point, beside its glossy lobes
// (material_eval.h evaluates those, lobe_sampling.h samples them): the base's mirror (Fresnel,
// faded out with roughness), the clearcoat's mirror, and the refraction of the transmissive share by
// exact dielectric Fresnel, one ray per colour channel into a dispersive volume. Each is a
// direction, a colour weight and the media the ray travels in next; the integrator traces them as
// listed and knows no material. Depends on scene and the material evaluation only.
#pragma once

#include <cstdint>

#include "scene/scene.h"
#include "shade/dielectric.h"
#include "shade/material_eval.h"
#include "shade/surface.h"

namespace kiln {

enum class delta_kind : uint8_t { mirror, coat_mirror, refraction };

struct delta_lobe {
  delta_kind kind = delta_kind::mirror;
  vec3 direction{0.0f};  // unit
  vec3 weight{0.0f};     // the traced ray's radiance times this is the lobe's share
  int channel = -1;      // the colour channel (0-2) the ray carries from here on; -1: all three
  medium_stack media;    // the closed volumes the ray travels in
  // A refraction's interface, for its ray cone: eta = n_incident / n_transmitted, and whether the
  // ray bends (a thin wall passes it on unbent).
  float eta = 1.0f;
  bool bends = false;
};

// At most one refraction per colour channel, the base's mirror and the coat's own.
constexpr int max_delta_lobes = 5;

// The delta lobes in the order they are traced: the refractions (one, or three by channel), then
// the base's mirror (always listed, its weight possibly zero; the coat's joins it when both reflect
// about the same normal), then the coat's mirror about its own normal.
struct delta_lobes {
  delta_lobe lobes[max_delta_lobes];
  int count = 0;
};

// The share of the base's reflection and transmission that reaches the viewer through the layers
// above it: the sheen's albedo scaling at the view and 1 − the coat's Fresnel weight.
float through_layers(const material_point& mp, float cos_theta, float coat_cos_theta);

// The delta lobes of the surface sp (material mp) for a ray arriving along the unit incident
// direction, inside media, carrying colour channel (-1: all). mirror_roughness_limit: the
// roughness at which the mirror has faded out (shading_options).
delta_lobes delta_lobes_at(const scene& s, float mirror_roughness_limit, const surface_point& sp,
                           const material_point& mp, const vec3& incident, const medium_stack& media,
                           int channel);

}  // namespace kiln
