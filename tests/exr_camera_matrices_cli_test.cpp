// The EXR header's worldToNDC and worldToCamera read back as a compositor reads them
// (ImfStandardAttributes.h: row vectors, p' = p·M with the homogeneous divide; NDC (0, 0) at the
// display window's upper-left corner and (1, 1) at its lower-right, y down; camera space
// left-handed, +Z the viewing direction). Every hit pixel's P must project onto that pixel's centre
// and lie at camera z equal to its planar depth, for perspective, orthographic and cropped renders.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "support/float_exr.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::gltf_builder;
using testing::run_kiln;
using testing::scratch_folder;

// glTF quaternion (x, y, z, w) of a turn by yaw about +Y after a pitch about +X (degrees).
std::array<double, 4> yaw_pitch(double yaw_degrees, double pitch_degrees) {
  const double y = yaw_degrees * M_PI / 360.0, p = pitch_degrees * M_PI / 360.0;
  // q_yaw · q_pitch with q_yaw = (0, sin y, 0, cos y), q_pitch = (sin p, 0, 0, cos p).
  return {std::cos(y) * std::sin(p), std::sin(y) * std::cos(p), -std::sin(y) * std::sin(p),
          std::cos(y) * std::cos(p)};
}

// A floor, a wall and a tilted panel at several depths, seen by a turned and tilted perspective
// camera ("persp") and an orthographic one ("ortho", xmag 4, ymag 3) from the same place.
std::string write_scene(const std::string& folder) {
  gltf_builder b;
  const int floor = b.add_mesh({{-6, 0, -8}, {6, 0, -8}, {6, 0, 4}, {-6, 0, 4}}, {0, 2, 1, 0, 3, 2});
  const int wall = b.add_mesh({{-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}}, {0, 1, 2, 0, 2, 3});
  const int panel =
      b.add_mesh({{1.5, 0.2, 0.5}, {3, 0.5, -0.5}, {3, 2.5, -1}, {1.5, 2, 0}}, {0, 1, 2, 0, 2, 3});
  const int persp = b.add_camera(
      {{"type", "perspective"}, {"name", "persp"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.1}}}});
  const int ortho =
      b.add_camera({{"type", "orthographic"},
                    {"name", "ortho"},
                    {"orthographic", {{"xmag", 4.0}, {"ymag", 3.0}, {"znear", 0.1}, {"zfar", 100.0}}}});
  b.add_node({{"mesh", floor}});
  b.add_node({{"mesh", wall}});
  b.add_node({{"mesh", panel}});
  const std::array<double, 4> q = yaw_pitch(25.0, -20.0);
  const nlohmann::json rotation = {q[0], q[1], q[2], q[3]};
  b.add_node({{"camera", persp}, {"translation", {3, 2.5, 6}}, {"rotation", rotation}});
  b.add_node({{"camera", ortho}, {"translation", {3, 2.5, 6}}, {"rotation", rotation}});
  const std::string path = folder + "/matrices.gltf";
  b.write(path);
  return path;
}

// p·M for a row-major 4x4 float matrix, as Imath's multVecMatrix computes it (before the divide).
std::array<double, 4> row_times(const double p[3], const float* m) {
  std::array<double, 4> h{};
  for (int c = 0; c < 4; ++c) h[c] = p[0] * m[c] + p[1] * m[4 + c] + p[2] * m[8 + c] + m[12 + c];
  return h;
}

struct matrix_errors {
  int hit_pixels = 0;
  double max_pixel_error = 0.0;    // |projected P - pixel centre|, pixels
  double min_camera_z = INFINITY;  // P·worldToCamera's z
  double max_depth_error = 0.0;    // |camera z - Z| / Z
};

// Renders with planar depth and one centre sample per pixel and checks every hit pixel.
matrix_errors measure(const std::string& scene, const std::string& folder, const std::string& name,
                      std::vector<std::string> extra) {
  const std::string out = folder + "/" + name + ".exr";
  std::vector<std::string> args = {"render",       scene,      "-o",    out,      "--width",
                                   "64",           "--height", "48",    "--aovs", "beauty,Z,P",
                                   "--depth-mode", "planar",   "--spp", "1",      "-q"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto result = run_kiln(args);
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  const testing::float_exr image = testing::read_float_exr(out);
  const OIIO::ImageSpec& spec = image.spec;
  const OIIO::ParamValue* ndc = spec.find_attribute("worldToNDC", OIIO::TypeMatrix44);
  const OIIO::ParamValue* cam = spec.find_attribute("worldToCamera", OIIO::TypeMatrix44);
  matrix_errors e;
  EXPECT_TRUE(ndc && cam) << out;
  if (!ndc || !cam) return e;
  const float* to_ndc = static_cast<const float*>(ndc->data());
  const float* to_camera = static_cast<const float*>(cam->data());
  const int z = spec.channelindex("Z"), px = spec.channelindex("P.X"), py = spec.channelindex("P.Y"),
            pz = spec.channelindex("P.Z");
  EXPECT_TRUE(z >= 0 && px >= 0 && py >= 0 && pz >= 0) << out;
  if (z < 0 || px < 0 || py < 0 || pz < 0) return e;
  for (int y = 0; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x) {
      const float* pixel = &image.pixels[(size_t(y) * spec.width + x) * spec.nchannels];
      if (!std::isfinite(pixel[z])) continue;  // background
      ++e.hit_pixels;
      const double p[3] = {pixel[px], pixel[py], pixel[pz]};
      const std::array<double, 4> h = row_times(p, to_ndc);
      // Display-window pixel coordinates of the point; pixel (i, j)'s centre is (i + 0.5, j + 0.5).
      const double sx = h[0] / h[3] * spec.full_width + spec.full_x;
      const double sy = h[1] / h[3] * spec.full_height + spec.full_y;
      const double cx = spec.x + x + 0.5, cy = spec.y + y + 0.5;
      e.max_pixel_error = std::max(e.max_pixel_error, std::hypot(sx - cx, sy - cy));
      const double camera_z = row_times(p, to_camera)[2];
      e.min_camera_z = std::min(e.min_camera_z, camera_z);
      e.max_depth_error = std::max(e.max_depth_error, std::abs(camera_z - pixel[z]) / pixel[z]);
    }
  std::printf("%s: %d hit pixels, max pixel error %.3g px, min camera z %.4g, max |z - Z|/Z %.3g\n",
              name.c_str(), e.hit_pixels, e.max_pixel_error, e.min_camera_z, e.max_depth_error);
  return e;
}

class exr_camera_matrices : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = scratch_folder("camera_matrices");
    scene_ = write_scene(folder_);
  }
  void expect_standard(const std::string& name, const std::vector<std::string>& extra, int min_hits) {
    const matrix_errors e = measure(scene_, folder_, name, extra);
    EXPECT_GE(e.hit_pixels, min_hits) << name;
    // P is stored as float (about 1e-6 relative at these distances): far below 0.01 px.
    EXPECT_LE(e.max_pixel_error, 0.01) << name;
    EXPECT_GT(e.min_camera_z, 0.0) << name << ": points in front of the camera must have z > 0";
    // Float P, float Z and a float matrix: 1e-5 relative covers their rounding.
    EXPECT_LE(e.max_depth_error, 1e-5) << name;
  }
  std::string folder_, scene_;
};

TEST_F(exr_camera_matrices, perspective_points_project_onto_their_pixel_centres) {
  expect_standard("persp", {"--camera", "persp"}, 1500);
}

TEST_F(exr_camera_matrices, orthographic_points_project_onto_their_pixel_centres) {
  expect_standard("ortho", {"--camera", "ortho"}, 1500);
}

TEST_F(exr_camera_matrices, look_at_camera_points_project_onto_their_pixel_centres) {
  expect_standard("look_at", {"--look-from", "-4,3,5", "--look-at", "0.5,0.5,-1", "--up", "0,1,0.2"}, 1500);
}

// NDC spans the display window (the full frame), not the crop's data window.
TEST_F(exr_camera_matrices, cropped_points_project_onto_their_full_frame_pixel_centres) {
  expect_standard("persp_crop", {"--camera", "persp", "--crop", "10,5,50,40"}, 600);
  expect_standard("ortho_crop", {"--camera", "ortho", "--crop", "3,20,61,47"}, 600);
  expect_standard("band", {"--camera", "persp", "--band", "2/3"}, 400);
}

}  // namespace
}  // namespace kiln
