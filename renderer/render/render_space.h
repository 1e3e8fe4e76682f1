// Camera-relative render space: the world translated so that the camera's eye is at the origin.
// Backends take float rays and float object-to-world transforms; far from the world origin those
// floats lose the scene's detail (a float at 1e6 is spaced 0.0625 apart) and the error bounds of
// hit points grow with the distance. Near the camera, where the image is made, render space keeps
// full precision. The translation is applied once, in double, to the prepared scene; the outputs
// that are positions (the P AOV, worldToCamera, worldToNDC) add it back. Depends on render/view_camera.
#pragma once

#include "render/view_camera.h"
#include "scene/scene.h"

namespace kiln {

// Translates every instance, light and glTF camera of s, and cam, by -cam.eye (in double), so
// that cam.eye becomes the origin; s.render_origin accumulates the world position of the origin.
void move_to_render_space(scene& s, view_camera& cam);

// The camera as it sits in world space: cam (in s's render space) with the render origin added.
view_camera world_space_view(const view_camera& cam, const scene& s);

}  // namespace kiln
