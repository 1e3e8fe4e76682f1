// The motion AOV end to end (`kiln render --aovs motion`): Nuke's forward.u/v and backward.u/v in
// pixels, u right and v up, against closed forms under an orthographic camera that maps one world
// unit to 8 pixels: a sliding quad, a quad whose edge a morph target moves, a spinning quad, and a
// sliding camera over a still quad. Background is 0, a still file has no motion, and a frame of a
// sequence carries the motion of the same frame rendered alone.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "support/animated_gltf.h"
#include "support/channel_exr.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::add_camera;
using testing::animate;
using testing::channel_exr;
using testing::gltf_builder;
using testing::render_float_exr;
using testing::scratch_folder;
using testing::sliding_and_morphing;
using testing::spinning;

constexpr int side = 16;
constexpr double pixels_per_unit = side / 2.0;  // xmag = ymag = 1
constexpr int fps = 5;                          // a frame is 0.2 s
constexpr double frame_seconds = 1.0 / fps;
// Frame 3 (t = 0.4 s): its neighbours at 0.2 s and 0.6 s lie inside every animation's keys (0..1 s).
const std::vector<std::string> frame_three = {"--fps", std::to_string(fps), "--frame", "3"};
constexpr float tolerance = 1e-3f;  // pixels: float positions, double projection

TEST(motion_vectors_cli, a_sliding_and_a_morphing_quad_move_as_the_closed_form_says) {
  const std::string dir = scratch_folder("motion_slide_morph");
  std::vector<std::string> extra = frame_three;
  extra.insert(extra.end(), {"--aovs", "beauty,P,motion"});
  const channel_exr image = render_float_exr(sliding_and_morphing(dir), dir + "/out.exr", side, side, extra);
  ASSERT_EQ(image.count(), size_t(side * side));
  const double t = 0.4;
  int slid = 0, morphed = 0, background = 0;
  for (size_t i = 0; i < image.count(); ++i) {
    SCOPED_TRACE(i);
    const float forward_u = image.at(i, "forward.u"), backward_u = image.at(i, "backward.u");
    EXPECT_EQ(image.at(i, "forward.v"), 0.0f);
    EXPECT_EQ(image.at(i, "backward.v"), 0.0f);
    if (image.at(i, "A") == 0.0f) {
      EXPECT_EQ(forward_u, 0.0f);
      EXPECT_EQ(backward_u, 0.0f);
      ++background;
      continue;
    }
    if (image.at(i, "P.Y") > 0.0f) {  // the slider: 1 unit a second, both ways alike
      EXPECT_NEAR(forward_u, pixels_per_unit * frame_seconds, tolerance);
      EXPECT_NEAR(backward_u, -pixels_per_unit * frame_seconds, tolerance);
      ++slid;
    } else {  // the morph: a point a share s of the way across moves 1.5·s a unit of weight
      const double s = (image.at(i, "P.X") + 1.0) / (0.5 + 1.5 * t);
      EXPECT_NEAR(forward_u, pixels_per_unit * 1.5 * s * frame_seconds, tolerance);
      EXPECT_NEAR(backward_u, -pixels_per_unit * 1.5 * s * frame_seconds, tolerance);
      ++morphed;
    }
  }
  EXPECT_GT(slid, 20);
  EXPECT_GT(morphed, 20);
  EXPECT_GT(background, 20);
}

TEST(motion_vectors_cli, a_spinning_quad_moves_each_point_along_its_circle) {
  const std::string dir = scratch_folder("motion_spin");
  std::vector<std::string> extra = frame_three;
  extra.insert(extra.end(), {"--aovs", "beauty,P,motion"});
  const channel_exr image = render_float_exr(spinning(dir), dir + "/out.exr", side, side, extra);
  const double turn = 0.5 * 3.14159265358979323846 * frame_seconds;  // a frame's angle
  int covered = 0;
  for (size_t i = 0; i < image.count(); ++i) {
    if (image.at(i, "A") == 0.0f) continue;
    SCOPED_TRACE(i);
    const double x = image.at(i, "P.X"), y = image.at(i, "P.Y");
    for (const auto& [layer, angle] :
         {std::pair<std::string, double>{"forward", turn}, {"backward", -turn}}) {
      const double moved_x = x * std::cos(angle) - y * std::sin(angle);
      const double moved_y = x * std::sin(angle) + y * std::cos(angle);
      // World y is up on this camera, as v is.
      EXPECT_NEAR(image.at(i, layer + ".u"), pixels_per_unit * (moved_x - x), tolerance) << layer;
      EXPECT_NEAR(image.at(i, layer + ".v"), pixels_per_unit * (moved_y - y), tolerance) << layer;
    }
    ++covered;
  }
  EXPECT_GT(covered, 40);
}

// A still quad over the whole view, and the camera sliding +1 in x a second: the picture moves the
// other way.
std::string sliding_camera(const std::string& folder) {
  gltf_builder b;
  b.add_node({{"mesh", b.add_mesh({{-3, -3, 0}, {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}}, {0, 1, 2, 0, 2, 3})}});
  animate(b, add_camera(b), "translation", {0, 0, 5}, {1, 0, 5});
  return b.write(folder + "/camera.gltf");
}

TEST(motion_vectors_cli, a_sliding_camera_moves_the_still_scene_the_other_way) {
  const std::string dir = scratch_folder("motion_camera");
  std::vector<std::string> extra = frame_three;
  extra.insert(extra.end(), {"--aovs", "beauty,motion"});
  const channel_exr image = render_float_exr(sliding_camera(dir), dir + "/out.exr", side, side, extra);
  for (size_t i = 0; i < image.count(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_NEAR(image.at(i, "forward.u"), -pixels_per_unit * frame_seconds, tolerance);
    EXPECT_NEAR(image.at(i, "backward.u"), pixels_per_unit * frame_seconds, tolerance);
    EXPECT_NEAR(image.at(i, "forward.v"), 0.0f, tolerance);
  }
}

// The pixel position of world point p through an EXR's worldToNDC (row vectors, as OpenEXR stores it).
std::array<double, 2> raster_through(const channel_exr& image, double x, double y, double z) {
  float m[16] = {};
  const OIIO::ParamValue* attribute = image.spec.find_attribute("worldToNDC", OIIO::TypeMatrix44);
  EXPECT_TRUE(attribute);
  if (attribute) std::memcpy(m, attribute->data(), sizeof m);
  const double p[4] = {x, y, z, 1.0};
  double out[4] = {};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c] += p[r] * m[r * 4 + c];
  return {out[0] / out[3] * image.spec.full_width, out[1] / out[3] * image.spec.full_height};
}

// No camera in the file: the default camera frames the union of the poses across the animation,
// so it holds still through the shot (frames 3 and 4 share one worldToNDC, which keeps the
// slider's whole path in view) and the still quad has no motion while the slider has its own.
TEST(motion_vectors_cli, the_default_camera_holds_still_through_the_shot) {
  const std::string dir = scratch_folder("motion_default_camera");
  gltf_builder b;
  b.add_node({{"mesh", b.add_mesh({{-2, -1, 0}, {-1, -1, 0}, {-1, 1, 0}, {-2, 1, 0}}, {0, 1, 2, 0, 2, 3})}});
  const int slide = b.add_mesh({{1, -1, 0}, {2, -1, 0}, {2, 1, 0}, {1, 1, 0}}, {0, 1, 2, 0, 2, 3});
  animate(b, b.add_node({{"mesh", slide}}), "translation", {0, 0, 0}, {2, 0, 0});
  const std::string scene = b.write(dir + "/no_camera.gltf");
  std::vector<std::string> extra = frame_three;
  extra.insert(extra.end(), {"--aovs", "beauty,P,motion"});
  const channel_exr now = render_float_exr(scene, dir + "/frame3.exr", side, side, extra);
  const channel_exr next =
      render_float_exr(scene, dir + "/frame4.exr", side, side,
                       {"--fps", std::to_string(fps), "--frame", "4", "--aovs", "beauty"});
  // The slider's far corner at its last key (x 4) and the still quad's (x -2) are in view.
  for (const double x : {4.0, -2.0}) {
    const auto corner = raster_through(now, x, 1.0, 0.0);
    EXPECT_GE(corner[0], 0.0);
    EXPECT_LE(corner[0], double(side));
  }
  int still = 0, moving = 0;
  for (size_t i = 0; i < now.count(); ++i) {
    if (now.at(i, "A") == 0.0f) continue;
    SCOPED_TRACE(i);
    const double x = now.at(i, "P.X"), y = now.at(i, "P.Y"), z = now.at(i, "P.Z");
    const auto from = raster_through(now, x, y, z), to = raster_through(next, x, y, z);
    EXPECT_NEAR(from[0], to[0], 1e-4);  // one view in both frames
    EXPECT_NEAR(from[1], to[1], 1e-4);
    if (x < -0.5) {
      EXPECT_EQ(now.at(i, "forward.u"), 0.0f);
      EXPECT_EQ(now.at(i, "forward.v"), 0.0f);
      ++still;
    } else {
      EXPECT_GT(now.at(i, "forward.u"), 0.05f);  // 2 units a second to the right
      ++moving;
    }
  }
  EXPECT_GT(still, 4);
  EXPECT_GT(moving, 4);
}

TEST(motion_vectors_cli, a_still_file_has_no_motion) {
  const std::string dir = scratch_folder("motion_still");
  gltf_builder b;
  b.add_node({{"mesh", b.add_mesh({{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}}, {0, 1, 2})}});
  add_camera(b);
  const channel_exr image = render_float_exr(b.write(dir + "/still.gltf"), dir + "/out.exr", side, side,
                                             {"--aovs", "beauty,motion"});
  int covered = 0;
  for (size_t i = 0; i < image.count(); ++i) {
    covered += image.at(i, "A") > 0.0f;
    for (const char* channel : {"forward.u", "forward.v", "backward.u", "backward.v"})
      EXPECT_EQ(image.at(i, channel), 0.0f) << i << " " << channel;
  }
  EXPECT_GT(covered, 10);
}

TEST(motion_vectors_cli, a_sequence_frame_carries_the_motion_of_the_frame_rendered_alone) {
  const std::string dir = scratch_folder("motion_sequence");
  const std::string scene = sliding_and_morphing(dir);
  const channel_exr alone =
      render_float_exr(scene, dir + "/alone.exr", side, side,
                       {"--fps", std::to_string(fps), "--frame", "3", "--aovs", "motion"});
  const auto sequence =
      testing::run_kiln({"render", scene, "-o", dir + "/shot.####.exr", "--width", std::to_string(side),
                         "--height", std::to_string(side), "-q", "--float", "--fps", std::to_string(fps),
                         "--frames", "2-4", "--aovs", "motion"});
  ASSERT_EQ(sequence.exit_code, 0) << sequence.stderr_text;
  const channel_exr in_sequence{testing::read_float_exr(dir + "/shot.0003.exr")};
  ASSERT_EQ(in_sequence.count(), alone.count());
  float largest = 0.0f;
  for (size_t i = 0; i < alone.count(); ++i)
    for (const char* channel : {"forward.u", "forward.v", "backward.u", "backward.v"}) {
      EXPECT_EQ(in_sequence.at(i, channel), alone.at(i, channel)) << i << " " << channel;
      largest = std::max(largest, std::abs(alone.at(i, channel)));
    }
  EXPECT_GT(largest, 1.0f);  // it moves
}

}  // namespace
}  // namespace kiln
