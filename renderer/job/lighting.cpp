#include "job/lighting.h"

#include <algorithm>

#include "core/error.h"
#include "io/file/shipped_file.h"

namespace kiln {

namespace {

// A point light at the camera that casts no shadows: its intensity is chosen so a white surface
// facing it at the scene centre reflects radiance ≈ 1.
void add_headlight(scene& world, const view_camera& cam) {
  bounds3 b = world_bounds(world);
  double distance = b.empty() ? 1.0 : std::max(glm::length(b.center() - cam.eye), 1e-6);
  light headlight;
  headlight.name = "headlight";  // its light group is lightgroup_headlight
  headlight.kind = light_kind::point;
  headlight.position = cam.eye;
  headlight.intensity = float(pi * distance * distance);
  headlight.casts_shadows = false;
  world.lights.push_back(headlight);
}

bool uses_studio(const render_options& options) {
  return options.lighting == "studio" ||
         (options.lighting == "auto" && options.environment.empty() && !options.background);
}

// What lights the environment gives, for the record.
std::string environment_description(const render_options& options) {
  if (uses_studio(options)) return "studio environment";
  if (!options.environment.empty()) return "environment map";
  const vec3 c = options.background.value_or(vec3(0.0f));
  return c.x > 0.0f || c.y > 0.0f || c.z > 0.0f ? "background colour" : "";
}

}  // namespace

std::vector<std::string> lighting_choices() { return {"auto", "studio", "headlight", "file"}; }

std::string job_environment_file(const render_options& options) {
  if (options.lighting == "studio" && (!options.environment.empty() || options.background))
    throw input_error(
        "", "--lighting",
        "studio lights the scene by kiln's own environment; drop --environment and --background, "
        "or choose --lighting auto");
  if (uses_studio(options)) return shipped_file("environments/studio.exr");
  return options.environment;
}

std::string apply_lighting(const render_options& options, scene& world, const view_camera& cam,
                           const std::function<void(const std::string&)>& warn) {
  if (options.lighting == "studio") world.lights.clear();
  std::string parts;
  if (!world.lights.empty()) parts = "file lights (" + std::to_string(world.lights.size()) + ")";
  if (options.lighting == "headlight" && world.lights.empty()) {
    add_headlight(world, cam);
    parts = "headlight";
    if (warn) warn("the file has no lights; using a headlight at the camera");
  }
  const std::string environment = environment_description(options);
  if (!environment.empty()) parts += (parts.empty() ? "" : " + ") + environment;
  if (parts.empty()) {
    if (warn)
      warn(
          "nothing lights the scene (the file has no lights and no environment was given); only emission is "
          "seen");
    return "none";
  }
  return parts;
}

}  // namespace kiln
