// Turntables and camera views end to end: `kiln render --turntable N` writes N EXRs whose camera
// (read back from worldToCamera) orbits the bounds' centre at one distance and elevation, at the
// stated azimuths; a frame is the look-at render from where it stands, and `--turntable N --frame F`
// (what kiln batch and the farm run) is that frame exactly; the asset never touches the image's
// border; an animation plays along unless held; --camera-view looks from the stated directions;
// bad values exit 2 with one line. Renders are 32x24 at one sample a pixel.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/float_exr.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::float_exr;
using testing::gltf_builder;
using testing::lines;
using testing::read_float_exr;
using testing::run_kiln;
using testing::scratch_folder;

constexpr double degrees = M_PI / 180.0;
using vec = std::array<double, 3>;

// The closed box [lo, hi] with outward, counter-clockwise faces.
int add_box(gltf_builder& b, const vec& lo, const vec& hi) {
  std::vector<std::array<float, 3>> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back(
        {float(i & 1 ? hi[0] : lo[0]), float(i & 2 ? hi[1] : lo[1]), float(i & 4 ? hi[2] : lo[2])});
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<uint32_t> indices;
  for (const auto& q : quads) indices.insert(indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  return b.add_mesh(corners, indices);
}

// A long, flat box away from the origin: its bounds' centre is (2, 1, -1.7), and from the side it
// is three times as wide as from the front. No camera, no light (kiln's studio lights it).
constexpr vec box_lo = {1.0, 0.5, -2.0}, box_hi = {3.0, 1.5, -1.4};
constexpr vec box_centre = {2.0, 1.0, -1.7};

std::string write_box(const std::string& folder) {
  gltf_builder b;
  b.add_node({{"mesh", add_box(b, box_lo, box_hi)}});
  return b.write(folder + "/box.gltf");
}

// The bounding sphere's framing distance for a 32x24 image at 45°: the vertical half-angle is the narrower.
double framing_distance(const vec& lo, const vec& hi) {
  const double radius =
      0.5 * std::sqrt(std::pow(hi[0] - lo[0], 2) + std::pow(hi[1] - lo[1], 2) + std::pow(hi[2] - lo[2], 2));
  return radius / std::sin(22.5 * degrees);
}

// The camera an EXR records: worldToCamera in row-vector form (p_camera = p · M), so row r of its
// 3x3 block is world axis r in camera space; the eye is where the camera is, view its +Z, up its +Y.
struct recorded_camera {
  std::array<float, 16> matrix{};
  vec eye{}, view{}, up{};
  std::string camera, frame, time_code;  // time_code: OpenEXR's timeCode as "hh:mm:ss:ff"
  double time = NAN;                     // kiln/time_seconds, a double
};

recorded_camera camera_of(const float_exr& image) {
  recorded_camera c;
  const OIIO::ParamValue* m = image.spec.find_attribute("worldToCamera", OIIO::TypeMatrix44);
  EXPECT_TRUE(m);
  if (!m) return c;
  const float* f = static_cast<const float*>(m->data());
  std::copy(f, f + 16, c.matrix.begin());
  for (int r = 0; r < 3; ++r) {
    c.eye[r] = -(f[12] * f[r * 4 + 0] + f[13] * f[r * 4 + 1] + f[14] * f[r * 4 + 2]);
    c.view[r] = f[r * 4 + 2];
    c.up[r] = f[r * 4 + 1];
  }
  c.camera = image.spec.get_string_attribute("kiln/camera");
  c.frame = std::to_string(image.spec.get_int_attribute("kiln/frame", -1));
  if (const OIIO::ParamValue* t = image.spec.find_attribute("kiln/time_seconds", OIIO::TypeDesc::DOUBLE))
    c.time = *static_cast<const double*>(t->data());
  if (const OIIO::ParamValue* t = image.spec.find_attribute("smpte:TimeCode")) c.time_code = t->get_string();
  return c;
}

recorded_camera camera_of(const std::string& path) { return camera_of(read_float_exr(path)); }

vec minus(const vec& a, const vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double length(const vec& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

// The angle a - b in degrees, brought into (-180, 180].
double angle_between(double a, double b) {
  double d = std::fmod(a - b, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d <= -180.0) d += 360.0;
  return d;
}

std::string frame_name(const std::string& folder, const std::string& stem, int frame) {
  char name[64];
  std::snprintf(name, sizeof name, "/%s.%04d.exr", stem.c_str(), frame);
  return folder + name;
}

std::vector<std::string> render_args(const std::string& scene, const std::string& out) {
  return {"render", scene, "-o", out, "--width", "32", "--height", "24", "-q"};
}

// Alpha by pixel.
std::vector<float> alpha_of(const float_exr& image) {
  const int a = image.spec.channelindex("A");
  std::vector<float> alpha;
  for (size_t i = 0; i < image.spec.image_pixels(); ++i)
    alpha.push_back(image.pixels[i * size_t(image.spec.nchannels) + size_t(a)]);
  return alpha;
}

TEST(turntable_cli, frames_orbit_the_centre_at_one_distance_and_elevation_at_the_stated_angles) {
  const std::string dir = scratch_folder("turntable_orbit");
  const std::string scene = write_box(dir);
  std::vector<std::string> args = render_args(scene, dir + "/tt.####.exr");
  args.insert(args.end(), {"--turntable", "6", "--turntable-start", "30", "--turntable-elevation", "35"});
  const auto result = run_kiln(args);
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_FALSE(std::filesystem::exists(frame_name(dir, "tt", 7)));
  const double distance = framing_distance(box_lo, box_hi);
  for (int frame = 1; frame <= 6; ++frame) {
    SCOPED_TRACE(frame);
    const recorded_camera c = camera_of(frame_name(dir, "tt", frame));
    EXPECT_EQ(c.frame, std::to_string(frame));
    EXPECT_EQ(c.time_code, "00:00:00:0" + std::to_string(frame - 1));  // from the first frame at 24 fps
    EXPECT_NE(c.camera.find("turntable frame " + std::to_string(frame) + " of 6"), std::string::npos)
        << c.camera;
    const vec offset = minus(c.eye, box_centre);
    // The matrix is float: a few parts in 1e7 of the distance.
    EXPECT_NEAR(length(offset), distance, 1e-5 * distance);
    EXPECT_NEAR(std::asin(offset[1] / length(offset)) / degrees, 35.0, 1e-4);
    const double azimuth = std::atan2(offset[0], offset[2]) / degrees;
    EXPECT_NEAR(angle_between(azimuth, 30.0 + 60.0 * (frame - 1)), 0.0, 1e-4);
    // It looks at the centre, +Y up (no roll).
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c.view[k], -offset[k] / length(offset), 1e-5);
    EXPECT_GT(c.up[1], 0.0);
    EXPECT_NEAR(c.view[0] * c.up[2] - c.view[2] * c.up[0], 0.0, 1e-5);  // camera x stays horizontal
  }
}

TEST(turntable_cli, a_frame_is_the_look_at_render_from_its_eye_and_its_frame_alone_is_the_same_file) {
  const std::string dir = scratch_folder("turntable_frame");
  const std::string scene = write_box(dir);
  std::vector<std::string> args = render_args(scene, dir + "/tt.####.exr");
  args.insert(args.end(), {"--turntable", "5", "--aovs", "beauty,Z,N,P"});
  ASSERT_EQ(run_kiln(args).exit_code, 0);
  const float_exr sequence_frame = read_float_exr(frame_name(dir, "tt", 3));
  const recorded_camera c = camera_of(sequence_frame);

  // The same frame alone: what kiln batch and the farm run for it. Every pixel and channel equal.
  std::vector<std::string> alone = render_args(scene, dir + "/alone.exr");
  alone.insert(alone.end(), {"--turntable", "5", "--frame", "3", "--aovs", "beauty,Z,N,P"});
  ASSERT_EQ(run_kiln(alone).exit_code, 0);
  const float_exr single = read_float_exr(dir + "/alone.exr");
  EXPECT_EQ(single.pixels, sequence_frame.pixels);
  EXPECT_EQ(camera_of(single).matrix, c.matrix);

  // A look-at camera from the recorded eye towards the centre: the same camera (to the float the
  // EXR stores) and the same picture.
  char from[128], at[128];
  std::snprintf(from, sizeof from, "%.9g,%.9g,%.9g", c.eye[0], c.eye[1], c.eye[2]);
  std::snprintf(at, sizeof at, "%.17g,%.17g,%.17g", box_centre[0], box_centre[1], box_centre[2]);
  std::vector<std::string> look = render_args(scene, dir + "/look.exr");
  look.insert(look.end(), {"--look-from", from, "--look-at", at, "--aovs", "beauty,Z,N,P"});
  const auto looked = run_kiln(look);
  ASSERT_EQ(looked.exit_code, 0) << looked.stderr_text;
  const float_exr look_at = read_float_exr(dir + "/look.exr");
  const recorded_camera l = camera_of(look_at);
  for (int k = 0; k < 16; ++k) EXPECT_NEAR(l.matrix[size_t(k)], c.matrix[size_t(k)], 1e-5) << k;
  const std::vector<float> a = alpha_of(sequence_frame), b = alpha_of(look_at);
  int covered = 0, differ = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    covered += a[i] > 0.5f;
    differ += std::abs(a[i] - b[i]) > 0.5f;
  }
  EXPECT_GT(covered, 20);
  EXPECT_LE(differ, 1);  // a pixel centre on an edge may fall either way of a 1e-7 move
}

// A textured asset's turntable builds its texture pyramids and its environment's tables once: the
// later frames keep the first frame's (their images are the ones its pose decoded, moved over) and
// say so, and each frame is still the file of its frame alone, which builds its own.
TEST(turntable_cli, a_textured_asset_builds_its_pyramids_once_and_each_frame_is_its_frame_alone) {
  const std::filesystem::path asset =
      std::filesystem::path(KILN_SHARED_ASSETS) / "BoxTextured/glTF/BoxTextured.gltf";
  if (!std::filesystem::is_regular_file(asset)) GTEST_SKIP() << asset << " is absent";
  const std::string dir = scratch_folder("turntable_textures");
  const std::vector<std::string> common = {"--width", "32",          "--height", "24",     "--spp",
                                           "4",       "--turntable", "3",        "--aovs", "beauty"};
  std::vector<std::string> args = {"render", asset.string(), "-o", dir + "/tt.####.exr"};
  args.insert(args.end(), common.begin(), common.end());
  const auto sequence = run_kiln(args);
  ASSERT_EQ(sequence.exit_code, 0) << sequence.stderr_text;
  const std::vector<std::string> said = lines(sequence.stderr_text);
  int kept = 0;
  for (const std::string& line : said) {
    if (line.rfind("kiln: frame 1: ", 0) == 0) EXPECT_EQ(line.find("kept:"), std::string::npos);
    // Under the default studio lighting the environment's tables are kept beside the pyramids.
    if (line.rfind("kiln: frame ", 0) == 0 &&
        line.find("; kept: texture pyramids, environment tables") != std::string::npos)
      ++kept;
  }
  EXPECT_EQ(kept, 2) << sequence.stderr_text;

  std::vector<std::string> alone = {"render", asset.string(), "-o", dir + "/alone.exr", "-q", "--frame", "3"};
  alone.insert(alone.end(), common.begin(), common.end());
  ASSERT_EQ(run_kiln(alone).exit_code, 0);
  const float_exr single = read_float_exr(dir + "/alone.exr");
  const float_exr third = read_float_exr(frame_name(dir, "tt", 3));
  EXPECT_EQ(single.pixels, third.pixels);
  float lowest = 1.0f, highest = 0.0f;  // the texture shows: its pixels are not one colour
  for (size_t i = 0; i < third.pixels.size(); i += 4) {
    if (third.pixels[i + 3] < 0.999f) continue;
    lowest = std::min(lowest, third.pixels[i]);
    highest = std::max(highest, third.pixels[i]);
  }
  EXPECT_GT(highest - lowest, 0.05f);
}

TEST(turntable_cli, the_asset_stays_inside_the_frame_at_every_angle) {
  const std::string dir = scratch_folder("turntable_inside");
  const std::string scene = write_box(dir);
  for (const char* elevation : {"0", "20", "60", "90"}) {
    SCOPED_TRACE(elevation);
    std::vector<std::string> args = render_args(scene, dir + "/in.####.exr");
    args.insert(args.end(), {"--turntable", "8", "--turntable-elevation", elevation});
    ASSERT_EQ(run_kiln(args).exit_code, 0);
    for (int frame = 1; frame <= 8; ++frame) {
      SCOPED_TRACE(frame);
      const std::vector<float> alpha = alpha_of(read_float_exr(frame_name(dir, "in", frame)));
      int covered = 0, border = 0;
      for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x) {
          const float a = alpha[size_t(y) * 32 + size_t(x)];
          covered += a > 0.0f;
          if (x == 0 || y == 0 || x == 31 || y == 23) border += a > 0.0f;
        }
      EXPECT_GT(covered, 15);
      EXPECT_EQ(border, 0);
    }
  }
}

TEST(turntable_cli, camera_views_look_from_the_front_the_three_quarter_and_the_top) {
  const std::string dir = scratch_folder("camera_views");
  const std::string scene = write_box(dir);
  const auto view = [&](const std::string& name) {
    std::vector<std::string> args = render_args(scene, dir + "/" + name + ".exr");
    if (name != "default") args.insert(args.end(), {"--camera-view", name});
    const auto result = run_kiln(args);
    EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
    return camera_of(dir + "/" + name + ".exr");
  };
  // The front view is the default camera, to the bit.
  const recorded_camera standard = view("default"), front = view("front");
  EXPECT_EQ(front.matrix, standard.matrix);
  EXPECT_EQ(front.camera, "front view (azimuth 0, elevation 0)");
  const recorded_camera quarter = view("three-quarter");
  const vec toward = {-std::sin(45 * degrees) * std::cos(25 * degrees), -std::sin(25 * degrees),
                      -std::cos(45 * degrees) * std::cos(25 * degrees)};
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(quarter.view[k], toward[k], 1e-6) << k;
  EXPECT_NEAR(length(minus(quarter.eye, box_centre)), length(minus(front.eye, box_centre)), 1e-5);
  // From above, the front of the asset (+Z) at the bottom of the image.
  const recorded_camera top = view("top");
  EXPECT_NEAR(top.view[1], -1.0, 1e-6);
  EXPECT_NEAR(top.up[2], -1.0, 1e-6);
  EXPECT_NEAR(view("90,0").view[0], -1.0, 1e-6);
}

// A box sliding +4 in x over the first second (frames 1 to 5 at 4 fps): played, the turntable
// poses frame F at (F - 1) / 4 s and frames every pose; held, every frame shows the rest pose,
// framed on it alone.
TEST(turntable_cli, an_animated_asset_plays_along_unless_held) {
  const std::string dir = scratch_folder("turntable_animated");
  gltf_builder b;
  const int node = b.add_node({{"mesh", add_box(b, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5})}});
  const int times = b.add_data(std::vector<float>{0, 1}, 5126, "SCALAR", 1);
  const int moves = b.add_data(std::vector<float>{0, 0, 0, 4, 0, 0}, 5126, "VEC3", 3);
  b.doc["animations"].push_back(
      {{"samplers", {{{"input", times}, {"output", moves}}}},
       {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}}}}});
  const std::string scene = b.write(dir + "/slide.gltf");
  for (const std::string mode : {"play", "hold"}) {
    SCOPED_TRACE(mode);
    std::vector<std::string> args = render_args(scene, dir + "/" + mode + ".####.exr");
    args.insert(args.end(), {"--turntable", "5", "--fps", "4", "--turntable-animation", mode});
    const auto result = run_kiln(args);
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    for (int frame = 1; frame <= 5; ++frame) {
      SCOPED_TRACE(frame);
      const float_exr image = read_float_exr(frame_name(dir, mode, frame));
      const recorded_camera c = camera_of(image);
      const double seconds = mode == "play" ? (frame - 1) / 4.0 : 0.0;
      EXPECT_NEAR(c.time, seconds, 1e-12);
      // The orbit's centre: the middle of the motion's bounds played, the rest pose's held.
      const vec centre = mode == "play" ? vec{2.0, 0.0, 0.0} : vec{0.0, 0.0, 0.0};
      const vec corner_hi = mode == "play" ? vec{4.5, 0.5, 0.5} : vec{0.5, 0.5, 0.5};
      const vec offset = minus(c.eye, centre);
      EXPECT_NEAR(length(offset), framing_distance({-0.5, -0.5, -0.5}, corner_hi), 1e-4);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(c.view[k], -offset[k] / length(offset), 1e-5);
      // Whatever the pose, the box is in the frame and off its border.
      const std::vector<float> alpha = alpha_of(image);
      int covered = 0, border = 0;
      for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x) {
          covered += alpha[size_t(y) * 32 + size_t(x)] > 0.0f;
          if (x == 0 || y == 0 || x == 31 || y == 23) border += alpha[size_t(y) * 32 + size_t(x)] > 0.0f;
        }
      EXPECT_GT(covered, 0);
      EXPECT_EQ(border, 0);
    }
  }
}

TEST(turntable_cli, motion_vectors_follow_the_turning_camera) {
  const std::string dir = scratch_folder("turntable_motion");
  const std::string scene = write_box(dir);
  std::vector<std::string> args = render_args(scene, dir + "/m.####.exr");
  args.insert(args.end(), {"--turntable", "12", "--frames", "2", "--aovs", "beauty,motion"});
  const auto result = run_kiln(args);
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const float_exr image = read_float_exr(frame_name(dir, "m", 2));
  const int a = image.spec.channelindex("A"), u = image.spec.channelindex("forward.u");
  ASSERT_GE(u, 0);
  // The asset holds still and the camera turns 30° a frame: the box turns across the image (only
  // what lies near the vertical axis through its centre keeps its place).
  int covered = 0, moving = 0;
  for (size_t i = 0; i < image.spec.image_pixels(); ++i) {
    const float* p = &image.pixels[i * size_t(image.spec.nchannels)];
    if (p[a] < 1.0f) continue;
    ++covered;
    moving += std::abs(p[u]) > 0.5f;
  }
  EXPECT_GT(covered, 10);
  EXPECT_GT(2 * moving, covered);
  // The same view held still (a look-at camera from there) moves nothing.
  const recorded_camera c = camera_of(image);
  char from[128];
  std::snprintf(from, sizeof from, "%.9g,%.9g,%.9g", c.eye[0], c.eye[1], c.eye[2]);
  std::vector<std::string> still = render_args(scene, dir + "/still.exr");
  still.insert(still.end(), {"--look-from", from, "--look-at", "2,1,-1.7", "--aovs", "beauty,motion"});
  ASSERT_EQ(run_kiln(still).exit_code, 0);
  const float_exr held = read_float_exr(dir + "/still.exr");
  for (size_t i = 0; i < held.spec.image_pixels(); ++i)
    EXPECT_EQ(held.pixels[i * size_t(held.spec.nchannels) + size_t(held.spec.channelindex("forward.u"))],
              0.0f);
}

TEST(turntable_cli, bad_turntables_and_views_exit_2_with_one_line_and_write_nothing) {
  const std::string dir = scratch_folder("turntable_errors");
  const std::string scene = write_box(dir);
  struct bad_case {
    std::vector<std::string> args;
    std::string out;
    const char* says;
  };
  const std::vector<bad_case> cases = {
      {{"--turntable", "0"}, "/t.####.exr", "--turntable"},
      {{"--turntable", "abc"}, "/t.####.exr", "--turntable"},
      {{"--turntable", "2000000"}, "/t.####.exr", "--turntable"},
      {{"--turntable", "4"}, "/plain.exr", "has no frame placeholder"},
      {{"--turntable", "4", "--frame", "9"}, "/t.exr", "not one of the turntable's frames 1-4"},
      {{"--turntable", "4", "--frame-start", "10", "--frame", "2"}, "/t.exr", "frames 10-13"},
      {{"--turntable", "4", "--camera", "0"}, "/t.####.exr", "drop --camera"},
      {{"--turntable", "4", "--look-from", "0,0,5", "--look-at", "0,0,0"}, "/t.####.exr", "drop --look-from"},
      {{"--turntable", "4", "--camera-view", "top"}, "/t.####.exr", "give one of them"},
      {{"--turntable", "4", "--turntable-elevation", "95"}, "/t.####.exr", "--turntable-elevation"},
      {{"--turntable", "4", "--turntable-animation", "loop"}, "/t.####.exr", "--turntable-animation"},
      {{"--turntable-start", "10"}, "/t.exr", "only applies to --turntable"},
      {{"--turntable", "4", "--time", "0.5"}, "/t.####.exr", "--time and --turntable"},
      {{"--turntable", "4", "--shutter", "-0.25,0.25", "--spp", "4"}, "/t.####.exr", "--shutter"},
      {{"--camera-view", "sideways"}, "/t.exr", "expected front, three-quarter, top or AZIMUTH,ELEVATION"},
      {{"--camera-view", "10,95"}, "/t.exr", "--camera-view"},
      {{"--camera-view", "top", "--look-from", "0,0,5", "--look-at", "0,0,0"}, "/t.exr", "drop --look-from"},
  };
  for (const bad_case& c : cases) {
    SCOPED_TRACE(c.says);
    std::vector<std::string> args = render_args(scene, dir + c.out);
    args.insert(args.end(), c.args.begin(), c.args.end());
    const auto result = run_kiln(args);
    EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
    EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find(c.says), std::string::npos) << result.stderr_text;
  }
  size_t written = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    written += entry.path().extension() == ".exr";
  EXPECT_EQ(written, 0u);
}

// kiln batch: a turntable (on the command line or a manifest job's "turntable") is one job per
// frame, planned with --turntable N --frame F, each the frame the sequence renders.
TEST(turntable_cli, a_batch_turntable_is_one_job_per_frame_each_the_sequences_frame) {
  const std::string dir = scratch_folder("turntable_batch");
  const std::string scene = write_box(dir);
  std::ofstream(dir + "/jobs.json") << nlohmann::json(
      {{"defaults", {{"spp", 1}, {"width", 32}, {"height", 24}}},
       {"jobs", {{{"asset", scene}, {"turntable", 3}, {"overrides", {{"turntable-elevation", 40}}}}}}});
  const std::vector<std::string> batch = {"batch",     "--manifest", dir + "/jobs.json",
                                          "--out-dir", dir + "/out", "-q"};
  std::vector<std::string> plan = batch;
  plan.insert(plan.end(), {"--plan-only", dir + "/plan.json", "--no-estimates"});
  const auto planning = run_kiln(plan);
  ASSERT_EQ(planning.exit_code, 0) << planning.stderr_text;
  const nlohmann::json planned = nlohmann::json::parse(std::ifstream(dir + "/plan.json"));
  ASSERT_EQ(planned["jobs"].size(), 3u) << planned.dump(1);
  EXPECT_EQ(planned["jobs"][1]["name"], "box.0002");
  EXPECT_EQ(planned["jobs"][1]["output"], dir + "/out/box.0002.exr");
  const std::vector<std::string> render_args_2 = planned["jobs"][1]["render_args"];
  const auto has = [&](const std::string& a, const std::string& b) {
    for (size_t i = 0; i + 1 < render_args_2.size(); ++i)
      if (render_args_2[i] == a && render_args_2[i + 1] == b) return true;
    return false;
  };
  EXPECT_TRUE(has("--turntable", "3")) << planned.dump(1);
  EXPECT_TRUE(has("--frame", "2")) << planned.dump(1);
  EXPECT_TRUE(has("--turntable-elevation", "40")) << planned.dump(1);
  const auto ran = run_kiln(batch);
  ASSERT_EQ(ran.exit_code, 0) << ran.stderr_text;
  std::vector<std::string> sequence = render_args(scene, dir + "/seq.####.exr");
  sequence.insert(sequence.end(), {"--turntable", "3", "--turntable-elevation", "40"});
  ASSERT_EQ(run_kiln(sequence).exit_code, 0);
  for (int frame = 1; frame <= 3; ++frame) {
    SCOPED_TRACE(frame);
    const float_exr batched = read_float_exr(frame_name(dir + "/out", "box", frame));
    EXPECT_EQ(batched.pixels, read_float_exr(frame_name(dir, "seq", frame)).pixels);
    EXPECT_EQ(camera_of(batched).frame, std::to_string(frame));
  }
}

}  // namespace
}  // namespace kiln
