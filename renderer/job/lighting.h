// What lights a render (--lighting): the file's punctual lights, an environment (a map, a constant
// colour, or kiln's studio environment) and, as before environment lighting, a headlight. Decided
// once per job from its options and the loaded file; depends on scene and the job's options.
#pragma once

#include <functional>
#include <string>

#include "job/render_options.h"
#include "render/view_camera.h"
#include "scene/scene.h"

namespace kiln {

// --lighting's choices: auto (the file's lights and the environment given, else kiln's studio
// environment), studio (the studio environment alone), headlight (the file's lights, or a light at
// the camera when it has none; an environment only when given) and file (the file's lights and the
// environment given, nothing added).
std::vector<std::string> lighting_choices();

// The environment map the job reads: --environment, the studio environment (share/environments/
// studio.exr) where the lighting uses it, else empty (the --background colour, or none). Throws
// kiln::error (input) when --lighting studio is given with --environment or --background.
std::string job_environment_file(const render_options& options);

// Fits the loaded scene's lights to the lighting (clears the file's under studio, adds the headlight
// under headlight) and returns what lights it, as the EXR records it ("file lights (2) + studio
// environment"). warn (optional) hears a note when the headlight is added or nothing lights the scene.
std::string apply_lighting(const render_options& options, scene& world, const view_camera& cam,
                           const std::function<void(const std::string&)>& warn);

}  // namespace kiln
