// A unit analytic sphere (KILN_quadric) at the origin wearing one glTF material, lit by one
// directional light and seen along -z by parallel rays: at every ray the normal, the view and the
// light direction are known in closed form, so a material lobe's image can be checked ray by ray
// against the formula of its specification. The rays run through the whole path a render takes
// (glTF loader, Scene, Embree, Whitted shading); nothing else is in the scene, so mirror rays see
// the black default environment. Used by the material extensions' image tests.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/math.h"

namespace kiln::testing {

struct lobe_sphere {
  nlohmann::json material;              // the sphere's glTF material
  std::vector<std::string> extensions;  // added to extensionsUsed (the material's extensions)
  dvec3 to_light = glm::normalize(dvec3(0.3, 0.4, 1.0));  // unit, toward the directional light
  double illuminance = 2.0;                               // the light's intensity, lux
  int grid = 40;                                          // rays per side across the sphere's disk
  double max_radius = 0.95;  // rays farther than this from the disk's centre are left out (grazing)
  double min_radius = 0.0;   // and rays nearer than this (the sphere's tangent frame turns at its pole)
  // "sphere", or "disk": the unit disk at z = 0 facing +z (a thin surface lit from either side).
  std::string shape = "sphere";
  // Constant 4×4 RGBA images, written beside the file as PNGs; texture i reads image i, so the
  // material refers to them by their index here.
  std::vector<std::array<int, 4>> textures;
  // Rays are traced here; the camera ray hits the sphere at (x, y, √(1 − x² − y²)), the disk at
  // (x, y, 0).
};

// One ray's closed-form geometry and what kiln shaded there.
struct lobe_ray {
  dvec3 normal;     // unit, outward: (x, y, √(1 − x² − y²)); the disk's (0, 0, 1)
  dvec3 tangent;    // unit dp/du of the surface's parameterisation: the sphere's (−y, x, 0) / ρ
  dvec3 to_viewer;  // (0, 0, 1)
  dvec3 to_light;   // lobe_sphere::to_light
  vec3 radiance;    // kiln's radiance along the ray
};

// The scene as a .gltf in the tests' scratch folder (name keeps parallel tests apart); returns its path.
std::string write_lobe_sphere(const lobe_sphere& setup, const std::string& name);

// Loads write_lobe_sphere's file and traces every ray of the grid inside max_radius.
std::vector<lobe_ray> trace_lobe_sphere(const lobe_sphere& setup, const std::string& name);

}  // namespace kiln::testing
