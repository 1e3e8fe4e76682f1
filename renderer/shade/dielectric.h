// Smooth dielectric interfaces for Whitted refraction: exact (unpolarised)
// Fresnel reflectance, Snell's law with total internal reflection, Beer-Lambert
// absorption, and the stack of media a ray is inside. Pure functions of their
// arguments; depends on scene (for material iors) only.
#pragma once

#include <array>
#include <optional>

#include "scene/scene.h"

namespace kiln {

// Fresnel reflectance of a smooth interface for unpolarised light, from the
// Fresnel equations (Born & Wolf §1.5). cos_i is the cosine of the incident
// angle (>= 0), eta = n_incident / n_transmitted. Returns 1 beyond the critical
// angle (total internal reflection).
float fresnel_dielectric(float cos_i, float eta);

// Snell refraction of the unit incident direction d at a surface with unit
// normal n facing the incoming ray (dot(d, n) < 0), eta = n_incident /
// n_transmitted. Empty on total internal reflection. The result is unit length.
std::optional<vec3> refract_direction(const vec3& d, const vec3& n, float eta);

// Beer-Lambert transmittance over distance through a medium whose attenuation
// colour is reached after attenuation_distance (KHR_materials_volume): T =
// colour^(distance / attenuation_distance).
vec3 beer_transmittance(const vec3& attenuation_color, float attenuation_distance, float distance);

// The index of refraction kiln uses for a material: glTF allows ior 0 (no
// refraction data), kiln treats anything below 1 as 1.5, glTF's default.
float material_ior(const material& m);

// The closed volumes a ray is inside, innermost last. Entering a front face
// pushes the material, leaving through a back face removes that material
// wherever it sits in the stack, so touching and nested media (a glass of
// water, an air bubble in glass) resolve to the right pair of iors as long as
// each volume is closed. A camera starts in vacuum (an empty stack, ior 1).
// More than capacity nested volumes are ignored beyond the capacity.
struct medium_stack {
  static constexpr int capacity = 8;
  std::array<uint32_t, capacity> materials{};
  int size = 0;

  bool empty() const { return size == 0; }
  uint32_t innermost() const { return materials[size_t(size - 1)]; }
  bool contains(uint32_t m) const;
  medium_stack with(uint32_t m) const;     // after entering m
  medium_stack without(uint32_t m) const;  // after leaving m (its innermost entry)
  // Index of refraction of the innermost medium (1 for vacuum).
  float ior(const scene& s) const;
};

}  // namespace kiln
