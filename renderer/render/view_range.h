// The coordinate-range check of a whole view: the camera's ray origins, every instance's world
// bounds, and every instance's object space as rays from the camera or the scene reach it. Run
// before any accelerator is built, for every backend alike (scene/coordinate_range.h gives the
// limit and why). Depends on render/view_camera and scene.
#pragma once

#include <string>

#include "render/view_camera.h"
#include "scene/scene.h"

namespace kiln {

// The box every ray kiln traces may start in: the scene's world bounds, the camera's eye and,
// for an orthographic camera, its window.
bounds3 ray_origin_bounds(const scene& s, const view_camera& cam);

// Throws an input error naming the node (or camera_location, in camera_file, for the camera)
// when any coordinate a backend would see is beyond max_coordinate.
void check_view_range(const scene& s, const view_camera& cam, const std::string& camera_file,
                      const std::string& camera_location);

}  // namespace kiln
