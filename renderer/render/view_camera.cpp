#include "render/view_camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <utility>

#include "core/error.h"
#include "core/message_text.h"
#include "scene/coordinate_range.h"
#include "scene/shutter_motion.h"

namespace kiln {

namespace {

void check_image_size(int width, int height) {
  if (width <= 0 || height <= 0)
    throw input_error(
        "", "camera",
        "image size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
}

// Fills the perspective window for a vertical field of view at image-plane distance d = 1.
void set_perspective_window(view_camera& cam, double yfov_radians) {
  double aspect = double(cam.width) / double(cam.height);
  cam.distance = 1.0;
  cam.top = std::tan(0.5 * yfov_radians);
  cam.bottom = -cam.top;
  cam.right_edge = cam.top * aspect;
  cam.left = -cam.right_edge;
}

}  // namespace

view_camera make_look_at_camera(const dvec3& eye, const dvec3& target, const dvec3& up, double yfov_degrees,
                                int width, int height) {
  check_image_size(width, height);
  if (!is_finite(eye) || !is_finite(target) || !is_finite(up) || !std::isfinite(yfov_degrees))
    throw input_error("", "camera", "look-at parameters must be finite numbers");
  if (!(yfov_degrees > 0.0 && yfov_degrees < 180.0))
    throw input_error("", "camera",
                      "field of view must be between 0 and 180 degrees, got " + std::to_string(yfov_degrees));
  dvec3 view = target - eye;
  double length = glm::length(view);
  if (!(length > 0.0)) throw input_error("", "camera", "look-from and look-at are the same point");
  view /= length;
  dvec3 right = glm::cross(view, up);
  double right_length = glm::length(right);
  if (!(right_length > 1e-9 * glm::length(up)) || !(glm::length(up) > 0.0))
    throw input_error("", "camera", "up vector is zero or parallel to the view direction");
  view_camera cam;
  cam.eye = eye;
  cam.view = view;
  cam.right = right / right_length;
  cam.up = glm::cross(cam.right, view);  // re-orthogonalised u
  cam.width = width;
  cam.height = height;
  set_perspective_window(cam, glm::radians(yfov_degrees));
  return cam;
}

view_camera make_gltf_camera(const camera& c, int width, int height) {
  check_image_size(width, height);
  const dmat4& m = c.world_from_camera;
  view_camera cam;
  cam.kind = c.kind;
  cam.eye = dvec3(m[3]);
  cam.view = glm::normalize(transform_vector(m, dvec3(0, 0, -1)));
  dvec3 up = transform_vector(m, dvec3(0, 1, 0));
  cam.right = glm::normalize(glm::cross(cam.view, up));
  cam.up = glm::cross(cam.right, cam.view);
  cam.width = width;
  cam.height = height;
  if (!is_finite(cam.view) || !is_finite(cam.right) || !is_finite(cam.eye))
    throw input_error("", "camera " + quoted(c.name), "camera transform is degenerate");
  if (c.kind == projection::perspective) {
    if (!(c.yfov > 0.0f && c.yfov < pi))
      throw input_error("", "camera " + quoted(c.name), "yfov must be in (0, pi)");
    set_perspective_window(cam, c.yfov);
  } else {
    // glTF's xmag/ymag are half-extents of the view; the image aspect decides the width when the
    // two disagree, so pixels stay square.
    double aspect = double(width) / double(height);
    cam.distance = 0.0;
    cam.top = std::abs(double(c.ymag));
    cam.bottom = -cam.top;
    cam.right_edge = cam.top * aspect;
    cam.left = -cam.right_edge;
    if (!(cam.top > 0.0)) throw input_error("", "camera " + quoted(c.name), "ymag must be non-zero");
  }
  return cam;
}

namespace {

// The sphere about the bounds' centre through their corners (radius 1 about the origin for empty
// bounds), and how far from its centre a camera of vertical field of view yfov_degrees must stand for
// the sphere to fit the narrower of the two half-angles, so a portrait image frames the scene as
// well as a landscape one. The sphere frames the scene from every direction.
struct framing_sphere {
  dvec3 centre{0.0};
  double radius = 1.0;
  double distance = 1.0;
};

framing_sphere frame_bounds(const bounds3& scene_bounds, double yfov_degrees, int width, int height) {
  framing_sphere s;
  if (!scene_bounds.empty()) {
    s.centre = scene_bounds.center();
    s.radius = std::max(0.5 * glm::length(scene_bounds.diagonal()), 1e-6);
  }
  const double half_vertical = glm::radians(0.5 * yfov_degrees);
  const double half_horizontal = std::atan(std::tan(half_vertical) * double(width) / double(height));
  s.distance = s.radius / std::sin(std::min(half_vertical, half_horizontal));
  return s;
}

// Bounds near double's range overflow the distance (the loader keeps coordinates within 1e15;
// this names the cause should any scene get past it).
void check_framed(const bounds3& scene_bounds, const framing_sphere& s, const dvec3& eye, const char* which) {
  if (!is_finite(eye) || !is_finite(s.centre) || !std::isfinite(s.radius))
    throw input_error("", which,
                      "the scene's bounds reach " + format_coordinate(max_abs_coordinate(scene_bounds)) +
                          ", too far to frame (give --look-from and --look-at)");
}

// sin and cos of an angle in degrees, exact at multiples of 90° (a front or top view has no
// 6e-17 tilt).
std::pair<double, double> sin_cos_degrees(double degrees) {
  const double turned = std::fmod(degrees, 360.0);
  const double quarter = turned / 90.0;
  if (quarter == std::floor(quarter)) {
    static const double sines[4] = {0.0, 1.0, 0.0, -1.0};
    const int k = (int(quarter) % 4 + 4) % 4;
    return {sines[k], sines[(k + 1) % 4]};
  }
  const double radians = glm::radians(turned);
  return {std::sin(radians), std::cos(radians)};
}

}  // namespace

view_camera make_default_camera(const bounds3& scene_bounds, int width, int height) {
  check_image_size(width, height);
  const double yfov = 45.0;
  const framing_sphere s = frame_bounds(scene_bounds, yfov, width, height);
  // A flat scene seen edge-on would show nothing: such a scene is looked at from above (flat in
  // x-z, e.g. a ground plane) or from +X (flat in y-z) instead.
  dvec3 from(0, 0, 1), up(0, 1, 0);
  if (!scene_bounds.empty()) {
    const dvec3 extent = scene_bounds.diagonal();
    const double flat = 1e-6 * glm::length(extent);
    if (extent.y <= flat && extent.x > flat) {
      from = dvec3(0, 1, 0);
      up = dvec3(0, 0, -1);
    } else if (extent.x <= flat && extent.y > flat) {
      from = dvec3(1, 0, 0);
    }
  }
  const dvec3 eye = s.centre + s.distance * from;
  check_framed(scene_bounds, s, eye, "default camera");
  return make_look_at_camera(eye, s.centre, up, yfov, width, height);
}

dvec3 orbit_direction(double azimuth_degrees, double elevation_degrees) {
  const auto [sin_azimuth, cos_azimuth] = sin_cos_degrees(azimuth_degrees);
  const auto [sin_elevation, cos_elevation] = sin_cos_degrees(elevation_degrees);
  return {sin_azimuth * cos_elevation, sin_elevation, cos_azimuth * cos_elevation};
}

view_camera make_orbit_camera(const bounds3& scene_bounds, double azimuth_degrees, double elevation_degrees,
                              double yfov_degrees, int width, int height) {
  check_image_size(width, height);
  if (!std::isfinite(azimuth_degrees) || !(std::abs(elevation_degrees) <= 90.0))
    throw input_error("", "camera", "orbit angles must be finite, the elevation within ±90 degrees");
  if (!(yfov_degrees > 0.0 && yfov_degrees < 180.0))
    throw input_error("", "camera",
                      "field of view must be between 0 and 180 degrees, got " + std::to_string(yfov_degrees));
  const framing_sphere s = frame_bounds(scene_bounds, yfov_degrees, width, height);
  const dvec3 from = orbit_direction(azimuth_degrees, elevation_degrees);
  // +Y is up; looking nearly straight down or up, the image's up is the direction the elevation
  // turns the view towards (at +90° the side facing azimuth + 180°: -Z for a top view from the
  // front), which is what +Y gives in the limit, so the two agree where they meet.
  dvec3 up(0, 1, 0);
  if (std::abs(elevation_degrees) > 80.0) {
    const auto [sin_azimuth, cos_azimuth] = sin_cos_degrees(azimuth_degrees);
    const auto [sin_elevation, cos_elevation] = sin_cos_degrees(elevation_degrees);
    up = dvec3(-sin_azimuth * sin_elevation, cos_elevation, -cos_azimuth * sin_elevation);
  }
  const dvec3 eye = s.centre + s.distance * from;
  check_framed(scene_bounds, s, eye, "camera");
  return make_look_at_camera(eye, s.centre, up, yfov_degrees, width, height);
}

view_camera view_at_time(const std::vector<view_camera>& steps, float time) {
  if (steps.size() < 2) return steps.empty() ? view_camera() : steps.front();
  const shutter_interval at = interval_at(uint32_t(steps.size()), time);
  const view_camera& a = steps[at.step];
  const view_camera& b = steps[at.step + 1];
  const double f = at.fraction;
  auto mix = [f](double x, double y) { return x + f * (y - x); };
  view_camera cam = a;
  cam.eye = a.eye + f * (b.eye - a.eye);
  // (right, up, -view) is a rotation: the camera's own frame, as glTF places it.
  const glm::dquat qa = glm::quat_cast(dmat3(a.right, a.up, -a.view));
  const glm::dquat qb = glm::quat_cast(dmat3(b.right, b.up, -b.view));
  const dmat3 frame = glm::mat3_cast(glm::slerp(qa, qb, f));
  cam.right = frame[0];
  cam.up = frame[1];
  cam.view = -frame[2];
  cam.left = mix(a.left, b.left);
  cam.right_edge = mix(a.right_edge, b.right_edge);
  cam.bottom = mix(a.bottom, b.bottom);
  cam.top = mix(a.top, b.top);
  cam.distance = mix(a.distance, b.distance);
  return cam;
}

void generate_camera_ray(const view_camera& cam, double px, double py, ray& out) {
  // Lower-left corner of the window and the point at fraction (sx, sy) across it.
  dvec3 lower_left = cam.eye + cam.distance * cam.view + cam.left * cam.right + cam.bottom * cam.up;
  double sx = px / cam.width;
  double sy = 1.0 - py / cam.height;  // image rows run top-down, the window's u axis bottom-up
  dvec3 on_window =
      lower_left + (cam.right_edge - cam.left) * sx * cam.right + (cam.top - cam.bottom) * sy * cam.up;
  out.kind = ray_kind::camera;
  if (cam.kind == projection::orthographic) {
    out.origin = vec3(on_window);
    out.direction = vec3(cam.view);
  } else {
    out.origin = vec3(cam.eye);
    out.direction = vec3(glm::normalize(on_window - cam.eye));
  }
}

ray generate_camera_ray(const view_camera& cam, double px, double py) {
  ray r;
  generate_camera_ray(cam, px, py, r);
  return r;
}

pixel_cone camera_pixel_cone(const view_camera& cam) {
  const double pixel = (cam.top - cam.bottom) / cam.height;  // window units per pixel
  if (cam.kind == projection::orthographic) return {pixel, 0.0};
  return {0.0, pixel / cam.distance};
}

dmat4 world_to_camera(const view_camera& cam) {
  // Rows right, up, view (column-vector form): camera x = (p - eye)·right and so on. The basis
  // (right, up, view) is left-handed, as OpenEXR and RenderMan define camera space.
  dmat4 m(1.0);
  const dvec3 axes[3] = {cam.right, cam.up, cam.view};
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 3; ++column) m[column][row] = axes[row][column];
    m[3][row] = -glm::dot(axes[row], cam.eye);
  }
  return m;
}

dmat4 world_to_ndc(const view_camera& cam) {
  // Camera space to NDC. The window spans [left, right_edge] x [bottom, top] at distance d (the
  // plane through the eye for orthographic views); NDC x runs from the window's left edge (0) to
  // its right edge (1), NDC y from its top (0) down to its bottom (1), so raster position = NDC x
  // image size and pixel (i, j) has its centre at ((i + 0.5) / width, (j + 0.5) / height). The
  // window is the full frame whatever --crop renders, as the EXR's display window is.
  // NDC z (which OpenEXR discards) maps camera depth near..far to 0..1.
  const double near_plane = 0.01, far_plane = 1e5;
  const double width = cam.right_edge - cam.left, height = cam.top - cam.bottom;
  dmat4 p(0.0);  // p[column][row]
  if (cam.kind == projection::perspective) {
    // Homogeneous w = camera z: x_ndc = (d·x/z - left) / width, y_ndc = (top - d·y/z) / height.
    p[0][0] = cam.distance / width;
    p[2][0] = -cam.left / width;
    p[1][1] = -cam.distance / height;
    p[2][1] = cam.top / height;
    p[2][2] = far_plane / (far_plane - near_plane);
    p[3][2] = -far_plane * near_plane / (far_plane - near_plane);
    p[2][3] = 1.0;
  } else {
    p[0][0] = 1.0 / width;
    p[3][0] = -cam.left / width;
    p[1][1] = -1.0 / height;
    p[3][1] = cam.top / height;
    p[2][2] = 1.0 / (far_plane - near_plane);
    p[3][2] = -near_plane / (far_plane - near_plane);
    p[3][3] = 1.0;
  }
  return p * world_to_camera(cam);
}

}  // namespace kiln
