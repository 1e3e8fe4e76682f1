#include "render/view_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"

namespace kiln {
namespace {

// The lecture formulation written out independently of view_camera: basis v, u, x = v × u,
// window l, r, t, b at distance d, lower-left corner O = C + d·v + l·x + b·u, and the pixel
// centre of (i, j) (j counted from the top) at O + (r-l)(i+½)/W·x + (t-b)(H-j-½)/H·u.
dvec3 lecture_direction(dvec3 c, dvec3 target, dvec3 up_hint, double fov_deg, int w, int h, int i, int j) {
  dvec3 v = glm::normalize(target - c);
  dvec3 x = glm::normalize(glm::cross(v, up_hint));
  dvec3 u = glm::cross(x, v);
  double d = 1.0;
  double t = std::tan(glm::radians(fov_deg) / 2.0), b = -t;
  double r = t * double(w) / h, l = -r;
  dvec3 o = c + d * v + l * x + b * u;
  dvec3 p = o + (r - l) * (i + 0.5) / w * x + (t - b) * (h - j - 0.5) / h * u;
  return glm::normalize(p - c);
}

TEST(view_camera, camera_rays_match_the_lecture_formula) {
  dvec3 eye(1.0, 2.0, 3.0), target(-0.5, 0.25, -4.0), up(0.1, 1.0, 0.0);
  const int w = 64, h = 48;
  view_camera cam = make_look_at_camera(eye, target, up, 50.0, w, h);
  for (int j : {0, 7, 24, 47})
    for (int i : {0, 13, 32, 63}) {
      ray r = generate_camera_ray(cam, i + 0.5, j + 0.5);
      dvec3 expected = lecture_direction(eye, target, up, 50.0, w, h, i, j);
      EXPECT_NEAR(r.direction.x, expected.x, 1e-6);
      EXPECT_NEAR(r.direction.y, expected.y, 1e-6);
      EXPECT_NEAR(r.direction.z, expected.z, 1e-6);
      EXPECT_NEAR(r.origin.x, eye.x, 1e-6);
      EXPECT_NEAR(r.origin.y, eye.y, 1e-6);
      EXPECT_NEAR(r.origin.z, eye.z, 1e-6);
    }
}

TEST(view_camera, image_corners_span_the_field_of_view) {
  view_camera cam = make_look_at_camera(dvec3(0), dvec3(0, 0, -1), dvec3(0, 1, 0), 90.0, 100, 50);
  ray top_left = generate_camera_ray(cam, 0.0, 0.0);
  // 90° vertical: top edge at 45° up; aspect 2 puts the left edge at x = -2 on the d = 1 plane.
  EXPECT_NEAR(top_left.direction.y / -top_left.direction.z, 1.0, 1e-6);
  EXPECT_NEAR(top_left.direction.x / -top_left.direction.z, -2.0, 1e-6);
  ray centre = generate_camera_ray(cam, 50.0, 25.0);
  EXPECT_NEAR(centre.direction.z, -1.0f, 1e-7f);
}

TEST(view_camera, gltf_camera_looks_down_its_negative_z) {
  camera c;
  c.yfov = 0.5f;
  c.world_from_camera =
      glm::rotate(glm::translate(dmat4(1.0), dvec3(0, 0, 10)), glm::radians(90.0), dvec3(0, 1, 0));
  view_camera cam = make_gltf_camera(c, 32, 32);
  ray r = generate_camera_ray(cam, 16.0, 16.0);
  // Rotating -Z by +90° about Y gives -X.
  EXPECT_NEAR(r.direction.x, -1.0f, 1e-6f);
  EXPECT_NEAR(r.origin.z, 10.0f, 1e-6f);
}

TEST(view_camera, orthographic_rays_are_parallel_and_spread_over_the_window) {
  camera c;
  c.kind = projection::orthographic;
  c.xmag = 2.0f;
  c.ymag = 2.0f;
  view_camera cam = make_gltf_camera(c, 10, 10);
  ray a = generate_camera_ray(cam, 0.0, 0.0);
  ray b = generate_camera_ray(cam, 10.0, 10.0);
  EXPECT_EQ(a.direction, b.direction);
  EXPECT_NEAR(a.origin.x, -2.0f, 1e-6f);
  EXPECT_NEAR(a.origin.y, 2.0f, 1e-6f);
  EXPECT_NEAR(b.origin.x, 2.0f, 1e-6f);
  EXPECT_NEAR(b.origin.y, -2.0f, 1e-6f);
}

TEST(view_camera, default_camera_frames_every_corner_of_the_scene_bounds) {
  bounds3 box;
  box.extend(dvec3(-3, -1, -2));
  box.extend(dvec3(5, 2, 1));
  for (int w : {64, 32}) {  // landscape and portrait-ish images
    const int h = 48;
    view_camera cam = make_default_camera(box, w, h);
    const dmat4 ndc = world_to_ndc(cam);
    for (int corner = 0; corner < 8; ++corner) {
      dvec3 p((corner & 1) ? box.upper.x : box.lower.x, (corner & 2) ? box.upper.y : box.lower.y,
              (corner & 4) ? box.upper.z : box.lower.z);
      dvec4 corner_ndc = ndc * dvec4(p, 1.0);
      ASSERT_GT(corner_ndc.w, 0.0) << "corner " << corner << " is behind the camera";
      EXPECT_LE(std::abs(corner_ndc.x / corner_ndc.w - 0.5), 0.5)
          << "corner " << corner << " leaves the image sideways";
      EXPECT_LE(std::abs(corner_ndc.y / corner_ndc.w - 0.5), 0.5)
          << "corner " << corner << " leaves the image vertically";
    }
    // It looks at the centre: the centre pixel's ray passes through the box centre.
    ray r = generate_camera_ray(cam, 0.5 * w, 0.5 * h);
    dvec3 to_centre = glm::normalize(box.center() - dvec3(r.origin));
    EXPECT_NEAR(glm::dot(dvec3(r.direction), to_centre), 1.0, 1e-6);
  }
}

TEST(view_camera, default_camera_never_looks_at_a_flat_scene_edge_on) {
  // A ground plane (flat in x-z) is seen from above, a wall in y-z from +X; anything else from +Z.
  const struct {
    dvec3 lower, upper, view;
  } cases[] = {{{-1, 0, -1}, {1, 0, 1}, {0, -1, 0}},
               {{0, -1, -1}, {0, 1, 1}, {-1, 0, 0}},
               {{-1, -1, 0}, {1, 1, 0}, {0, 0, -1}},
               {{-1, -1, -1}, {1, 1, 1}, {0, 0, -1}}};
  for (const auto& c : cases) {
    bounds3 box;
    box.extend(c.lower);
    box.extend(c.upper);
    const view_camera cam = make_default_camera(box, 32, 32);
    EXPECT_NEAR(glm::dot(cam.view, c.view), 1.0, 1e-12) << c.view.x << "," << c.view.y << "," << c.view.z;
    const ray r = generate_camera_ray(cam, 16, 16);
    EXPECT_NEAR(glm::length(glm::cross(dvec3(r.direction), c.view)), 0.0, 1e-6);
  }
}

// Bounds at 1e308 overflow the framing distance; the error must say so, not blame look-at
// parameters the user never gave.
TEST(view_camera, bounds_too_large_to_frame_are_named) {
  bounds3 box;
  box.extend(dvec3(-1e308, 0, 0));
  box.extend(dvec3(1e308, 1, 1));
  try {
    make_default_camera(box, 32, 32);
    ADD_FAILURE() << "framed bounds of 1e308";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::input);
    EXPECT_EQ(e.location(), "default camera");
    EXPECT_EQ(e.reason(),
              "the scene's bounds reach 1e+308, too far to frame (give --look-from and --look-at)");
  }
}

TEST(view_camera, impossible_cameras_are_input_errors) {
  EXPECT_THROW(make_look_at_camera(dvec3(0), dvec3(0), dvec3(0, 1, 0), 45, 10, 10), error);
  EXPECT_THROW(make_look_at_camera(dvec3(0), dvec3(0, 1, 0), dvec3(0, 1, 0), 45, 10, 10), error);
  EXPECT_THROW(make_look_at_camera(dvec3(0), dvec3(0, 0, -1), dvec3(0, 1, 0), 0, 10, 10), error);
  EXPECT_THROW(make_look_at_camera(dvec3(0), dvec3(0, 0, -1), dvec3(0, 1, 0), 180, 10, 10), error);
  EXPECT_THROW(make_look_at_camera(dvec3(NAN), dvec3(0, 0, -1), dvec3(0, 1, 0), 45, 10, 10), error);
  EXPECT_THROW(make_look_at_camera(dvec3(0), dvec3(0, 0, -1), dvec3(0, 1, 0), 45, 0, 10), error);
}

// OpenEXR's NDC: (0, 0) at the upper-left corner of the frame, (1, 1) at the lower-right.
TEST(view_camera, world_to_ndc_maps_window_corners_to_unit_square) {
  view_camera cam = make_look_at_camera(dvec3(0, 0, 5), dvec3(0), dvec3(0, 1, 0), 60.0, 40, 20);
  ray r = generate_camera_ray(cam, 40.0, 0.0);  // top-right corner
  dvec4 p = world_to_ndc(cam) * dvec4(dvec3(r.origin) + 3.0 * dvec3(r.direction), 1.0);
  EXPECT_NEAR(p.x / p.w, 1.0, 1e-5);
  EXPECT_NEAR(p.y / p.w, 0.0, 1e-5);
  dvec4 q = world_to_camera(cam) * dvec4(0, 0, 0, 1);
  EXPECT_NEAR(q.z, 5.0, 1e-12);  // in front of the camera: z > 0
}

// A point along the ray through raster position (px, py) projects back to (px / W, py / H), and its
// camera z is its depth along the view axis, for both projections and for turned cameras.
TEST(view_camera, world_to_ndc_inverts_the_camera_ray_and_camera_z_is_planar_depth) {
  camera ortho;
  ortho.kind = projection::orthographic;
  ortho.ymag = 1.5f;
  ortho.world_from_camera =
      glm::rotate(glm::translate(dmat4(1.0), dvec3(1, 2, 3)), 0.7, glm::normalize(dvec3(1, 2, -1)));
  const view_camera cameras[] = {
      make_look_at_camera(dvec3(1, -2, 4), dvec3(0.3, 0.1, -1), dvec3(0.2, 1, 0), 50.0, 64, 48),
      make_gltf_camera(ortho, 64, 48)};
  for (const view_camera& cam : cameras) {
    const dmat4 ndc = world_to_ndc(cam), to_camera = world_to_camera(cam);
    for (double px : {0.0, 0.5, 17.25, 63.5, 64.0})
      for (double py : {0.0, 0.5, 30.75, 48.0}) {
        const ray r = generate_camera_ray(cam, px, py);
        const dvec3 point = dvec3(r.origin) + 7.0 * dvec3(r.direction);
        const dvec4 h = ndc * dvec4(point, 1.0);
        EXPECT_NEAR(h.x / h.w * cam.width, px, 1e-4) << px << "," << py;
        EXPECT_NEAR(h.y / h.w * cam.height, py, 1e-4) << px << "," << py;
        const dvec4 c = to_camera * dvec4(point, 1.0);
        EXPECT_NEAR(c.z, glm::dot(point - cam.eye, cam.view), 1e-9);
        EXPECT_GT(c.z, 0.0);
        EXPECT_NEAR(c.x, glm::dot(point - cam.eye, cam.right), 1e-9);
        EXPECT_NEAR(c.y, glm::dot(point - cam.eye, cam.up), 1e-9);
      }
  }
}

// The perspective pixel cone spreads by the angle between neighbouring pixel centres at the image
// centre; an orthographic one is a pixel wide and does not spread.
TEST(view_camera, pixel_cone_is_one_pixel) {
  const int w = 64, h = 48;
  const view_camera cam = make_look_at_camera(dvec3(0.0), dvec3(0, 0, -1), dvec3(0, 1, 0), 50.0, w, h);
  const vec3 a = generate_camera_ray(cam, 0.5 * w, 0.5 * h).direction;
  const vec3 b = generate_camera_ray(cam, 0.5 * w, 0.5 * h + 1.0).direction;
  const double angle = std::acos(std::min(double(glm::dot(a, b)), 1.0));
  EXPECT_NEAR(camera_pixel_cone(cam).spread, angle, 1e-3 * angle);
  EXPECT_EQ(camera_pixel_cone(cam).width, 0.0);

  camera c;
  c.kind = projection::orthographic;
  c.ymag = 3.0f;
  const view_camera ortho = make_gltf_camera(c, w, h);
  const ray r0 = generate_camera_ray(ortho, 10.0, 10.0), r1 = generate_camera_ray(ortho, 10.0, 11.0);
  EXPECT_NEAR(camera_pixel_cone(ortho).width, glm::length(r1.origin - r0.origin), 1e-5);
  EXPECT_EQ(camera_pixel_cone(ortho).spread, 0.0);
}

}  // namespace
}  // namespace kiln

namespace kiln {
namespace {

// Every corner of box inside the image of cam.
void expect_corners_in_view(const view_camera& cam, const bounds3& box) {
  const dmat4 ndc = world_to_ndc(cam);
  for (int corner = 0; corner < 8; ++corner) {
    const dvec3 p((corner & 1) ? box.upper.x : box.lower.x, (corner & 2) ? box.upper.y : box.lower.y,
                  (corner & 4) ? box.upper.z : box.lower.z);
    const dvec4 h = ndc * dvec4(p, 1.0);
    ASSERT_GT(h.w, 0.0) << "corner " << corner << " is behind the camera";
    EXPECT_LE(std::abs(h.x / h.w - 0.5), 0.5) << "corner " << corner << " leaves the image sideways";
    EXPECT_LE(std::abs(h.y / h.w - 0.5), 0.5) << "corner " << corner << " leaves the image vertically";
  }
}

TEST(view_camera, orbit_camera_frames_every_corner_from_every_direction) {
  bounds3 box;
  box.extend(dvec3(-3, -1, -2));
  box.extend(dvec3(5, 2, 1));
  for (double elevation : {-90.0, -45.0, 0.0, 20.0, 85.0, 90.0})
    for (double azimuth = -180.0; azimuth < 360.0; azimuth += 22.5) {
      SCOPED_TRACE(std::to_string(azimuth) + ", " + std::to_string(elevation));
      const view_camera cam = make_orbit_camera(box, azimuth, elevation, 45.0, 48, 32);
      expect_corners_in_view(cam, box);
      // From the orbit's direction at one distance, looking at the centre.
      const dvec3 offset = cam.eye - box.center();
      EXPECT_NEAR(glm::dot(glm::normalize(offset), orbit_direction(azimuth, elevation)), 1.0, 1e-12);
      EXPECT_NEAR(glm::dot(cam.view, -glm::normalize(offset)), 1.0, 1e-12);
      EXPECT_NEAR(glm::length(offset),
                  glm::length(make_orbit_camera(box, 0, 0, 45.0, 48, 32).eye - box.center()), 1e-9);
    }
}

TEST(view_camera, orbit_camera_from_the_front_is_the_default_camera) {
  bounds3 box;
  box.extend(dvec3(-3, -1, -2));
  box.extend(dvec3(5, 2, 1));
  const view_camera front = make_orbit_camera(box, 0.0, 0.0, 45.0, 64, 48);
  const view_camera standard = make_default_camera(box, 64, 48);
  EXPECT_EQ(world_to_camera(front), world_to_camera(standard));
  EXPECT_EQ(world_to_ndc(front), world_to_ndc(standard));
}

TEST(view_camera, orbit_directions_and_ups) {
  EXPECT_EQ(orbit_direction(0, 0), dvec3(0, 0, 1));
  EXPECT_EQ(orbit_direction(90, 0), dvec3(1, 0, 0));
  EXPECT_EQ(orbit_direction(-90, 0), dvec3(-1, 0, 0));
  EXPECT_EQ(orbit_direction(180, 0), dvec3(0, 0, -1));
  EXPECT_EQ(orbit_direction(0, 90), dvec3(0, 1, 0));
  const double r = std::sqrt(0.5);
  EXPECT_NEAR(glm::length(orbit_direction(45, 0) - dvec3(r, 0, r)), 0.0, 1e-15);
  bounds3 box;
  box.extend(dvec3(-1, -1, -1));
  box.extend(dvec3(1, 1, 1));
  // From above, the front (+Z) at the bottom of the image: up is -Z.
  const view_camera top = make_orbit_camera(box, 0, 90, 45.0, 32, 32);
  EXPECT_EQ(top.view, dvec3(0, -1, 0));
  EXPECT_EQ(top.up, dvec3(0, 0, -1));
  // Seen from the side, +Y stays up.
  const view_camera side = make_orbit_camera(box, 90, 30, 45.0, 32, 32);
  EXPECT_GT(side.up.y, 0.8);
  EXPECT_NEAR(side.right.y, 0.0, 1e-12);  // no roll
  EXPECT_THROW(make_orbit_camera(box, 0, 91, 45.0, 32, 32), error);
  EXPECT_THROW(make_orbit_camera(box, std::nan(""), 0, 45.0, 32, 32), error);
}

}  // namespace
}  // namespace kiln
