// The range of coordinates kiln hands to a traversal backend. Embree 3.13 asserts (and this
// build aborts) on a ray whose origin or direction has a component beyond FLT_LARGE = 1.844e18,
// in world space or after an instance transform has carried it into object space. These checks
// run in double on the scene before any accelerator is built. Depends on scene and core only.
#pragma once

#include <optional>
#include <string>

#include "scene/scene.h"

namespace kiln {

// Embree 3.13's limit: RayK::valid() requires |org|, |dir| <= FLT_LARGE per component
// (kernels/common/ray.h, common/math/constants.h); its builders drop boxes beyond it.
constexpr double embree_coordinate_limit = 1.844e18;

// kiln's limit on every coordinate of the scene (object and world space), the camera and the
// lights, and on every ray once an instance transform has carried it into object space. It
// leaves a factor of ~1800 below Embree's for what the check cannot follow exactly: Embree
// inverts the float-rounded transform in float, hit points are offset by their error bounds, and
// the camera-relative render space adds the camera position (coordinates up to twice this).
constexpr double max_coordinate = 1e15;

// The largest absolute component of the box (0 for an empty box).
double max_abs_coordinate(const bounds3& b);

// Empty when a transform placing a shape keeps both directions in range: the float-rounded
// matrix Embree receives, its inverse, their linear parts (row norms: how far a unit direction
// goes) and the translation; otherwise the reason.
std::optional<std::string> transform_range_problem(const dmat4& world_from_object);

// Empty when every ray whose origin lies in `origins` (world space, or the space the instance
// is placed in) and whose direction is a unit vector stays within max_coordinate in the
// instance's object space; otherwise the reason.
std::optional<std::string> object_space_range_problem(const instance& inst, const bounds3& origins);

// "1.2e+20": a coordinate for a message.
std::string format_coordinate(double v);

}  // namespace kiln
