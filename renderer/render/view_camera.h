// Camera rays in the lecture formulation: a gluLookAt-style basis (v = view direction, u = up,
// x = v × u), an image-plane window l, r, t, b at distance d, and the lower-left corner
// O = C + d·v + l·x + b·u. Depends on core and scene (for glTF cameras).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/ray.h"
#include "scene/scene.h"

namespace kiln {

struct view_camera {
  projection kind = projection::perspective;
  dvec3 eye{0.0};                                                  // C
  dvec3 view{0.0, 0.0, -1.0};                                      // v, unit
  dvec3 up{0.0, 1.0, 0.0};                                         // u, unit, orthogonal to v
  dvec3 right{1.0, 0.0, 0.0};                                      // x = v × u
  double left = -1.0, right_edge = 1.0, bottom = -1.0, top = 1.0;  // window l, r, b, t
  double distance = 1.0;                                           // d
  int width = 1;
  int height = 1;
};

// Throws kiln::error (input) for impossible parameters (zero or straight fov, eye == target,
// up parallel to the view direction, non-finite values, non-positive image size).
view_camera make_look_at_camera(const dvec3& eye, const dvec3& target, const dvec3& up, double yfov_degrees,
                                int width, int height);

// A glTF camera: position and orientation from its world transform (looking along -Z, +Y up).
view_camera make_gltf_camera(const camera& c, int width, int height);

// The default when a file has no camera: looks along -Z at the centre of the scene bounds from
// far enough that the bounding sphere fills a 45° vertical field of view.
view_camera make_default_camera(const bounds3& scene_bounds, int width, int height);

// The unit direction from an orbit's centre to its camera: azimuth about +Y from +Z towards +X
// (counter-clockwise seen from above), elevation above the x-z plane. Exact at multiples of 90°.
dvec3 orbit_direction(double azimuth_degrees, double elevation_degrees);

// The default camera's framing from another direction: it looks at the centre of the scene bounds
// from orbit_direction(azimuth, elevation), as far back as the bounding sphere needs to fit the
// narrower half-angle of a yfov_degrees vertical field of view, so the whole scene is in view from
// any direction. Up is +Y (towards -Z, the far side, seen from straight above). Throws kiln::error
// (input) for an elevation past ±90°, a bad field of view or bounds too far to frame.
view_camera make_orbit_camera(const bounds3& scene_bounds, double azimuth_degrees, double elevation_degrees,
                              double yfov_degrees, int width, int height);

// The camera at `time` in the shutter (motion blur) among `steps` views evenly spaced over it: the
// eye and the window interpolated linearly, the orientation by shortest-path slerp, so the camera
// turns rigidly between steps. The views share projection and image size.
view_camera view_at_time(const std::vector<view_camera>& steps, float time);

// The ray through image position (px, py) in pixels, (0, 0) at the top-left corner of the image
// and (width, height) at the bottom-right; pixel (i, j) has its centre at (i + 0.5, j + 0.5).
ray generate_camera_ray(const view_camera& cam, double px, double py);

// generate_camera_ray written into `out` (its origin, direction and kind; the other fields are left
// as they are): a batch fills its rays in place rather than copying each one in whole from where it
// was just written field by field (a store-forwarding stall per ray).
void generate_camera_ray(const view_camera& cam, double px, double py, ray& out);

// A pixel's ray cone (Akenine-Möller et al., Ray Tracing Gems ch. 20): perspective rays start with
// width 0 and spread by the pixel angle, window height / (d · image height); orthographic rays are
// one pixel wide and do not spread.
struct pixel_cone {
  double width = 0.0;   // world units at the ray origin
  double spread = 0.0;  // radians
};
pixel_cone camera_pixel_cone(const view_camera& cam);

// World to camera space as OpenEXR's worldToCamera defines it (ImfStandardAttributes.h, RenderMan's
// camera space): left-handed, +X right, +Y up, +Z the viewing direction (points in front have z > 0).
// Column-vector form (p_camera = M · p); the EXR stores its transpose for row vectors.
dmat4 world_to_camera(const view_camera& cam);

// World to OpenEXR's (and RenderMan's) NDC: after the homogeneous divide, (0, 0) is the upper-left
// and (1, 1) the lower-right corner of the full frame (the display window), y pointing down.
dmat4 world_to_ndc(const view_camera& cam);

}  // namespace kiln
