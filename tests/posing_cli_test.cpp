// Time on the command line end to end: --time, --frame with --fps and --frame-start and
// --animation pose a quad that slides across an orthographic view, so which pixel columns it
// covers is known in closed form; the options reach the EXR header and the settings hash, and bad
// values or bad keyframes exit 2 with one line.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using nlohmann::json;
using testing::gltf_builder;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

constexpr int side = 8;

// A quad over x -1..0, y -1..1 at z = 0, its node sliding +1 along x from t = 0 to t = 1 (animation
// "slide"; animation "stay" holds it at x = -1), under an orthographic camera at z = 5 that
// sees x and y in -1..1. With `bad_times` the keyframe times do not increase.
std::string sliding_quad(const std::string& folder, bool bad_times = false) {
  gltf_builder b;
  const int mesh = b.add_mesh({{-1, -1, 0}, {0, -1, 0}, {0, 1, 0}, {-1, 1, 0}}, {0, 1, 2, 0, 2, 3});
  const int quad = b.add_node({{"mesh", mesh}});
  const int camera =
      b.add_camera({{"type", "orthographic"},
                    {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 100}}}});
  b.add_node({{"camera", camera}, {"translation", {0, 0, 5}}});
  const auto animation = [&](const char* name, std::vector<float> times, std::vector<float> values) {
    const int input = b.add_data(times, 5126, "SCALAR", 1);
    const int output = b.add_data(values, 5126, "VEC3", 3);
    b.doc["animations"].push_back(
        {{"name", name},
         {"samplers", {{{"input", input}, {"output", output}}}},
         {"channels", {{{"sampler", 0}, {"target", {{"node", quad}, {"path", "translation"}}}}}}});
  };
  animation("slide", bad_times ? std::vector<float>{1, 0} : std::vector<float>{0, 1}, {0, 0, 0, 1, 0, 0});
  animation("stay", {0, 1}, {-1, 0, 0, -1, 0, 0});
  return b.write(folder + "/quad.gltf");
}

// Every pixel's alpha.
std::vector<float> alpha_of(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  std::vector<float> alpha;
  for (size_t i = 0; i < size_t(spec.width) * spec.height; ++i)
    alpha.push_back(pixels[i * spec.nchannels + spec.channelindex("A")]);
  return alpha;
}

// Alpha of the middle row, column by column.
std::vector<float> middle_row_alpha(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  const int alpha = spec.channelindex("A");
  std::vector<float> row;
  for (int x = 0; x < spec.width; ++x)
    row.push_back(pixels[(size_t(spec.height / 2) * spec.width + x) * spec.nchannels + alpha]);
  return row;
}

// The attribute as OpenImageIO reads it, "TYPE VALUE" ("int 13", "double 0.5", "string stay"),
// or "" when the file has none.
std::string attribute(const std::string& path, const std::string& name) {
  auto in = OIIO::ImageInput::open(path);
  const OIIO::ParamValue* value = in ? in->spec().find_attribute(name) : nullptr;
  return value ? std::string(value->type().c_str()) + " " + value->get_string() : "";
}

// Columns whose centres, x = -1 + (i + 0.5) / 4, lie in the quad's span [-1 + t, t] at time t.
std::vector<float> expected_row(double t) {
  std::vector<float> row;
  for (int i = 0; i < side; ++i) {
    const double x = -1.0 + (i + 0.5) * 2.0 / side;
    row.push_back(x >= -1.0 + t && x <= t ? 1.0f : 0.0f);
  }
  return row;
}

std::vector<std::string> render_args(const std::string& scene, const std::string& out) {
  return {"render", scene, "-o", out, "--width", std::to_string(side), "--height", std::to_string(side),
          "-q"};
}

TEST(posing_cli, time_and_frame_pose_the_scene_where_the_closed_form_says) {
  const std::string dir = scratch_folder("posing_time");
  const std::string scene = sliding_quad(dir);
  struct run_case {
    std::vector<std::string> args;
    double t;
  };
  const std::vector<run_case> cases = {
      {{}, 0.0},                                                    // no time: t = 0
      {{"--time", "0.5"}, 0.5},                                     // halfway
      {{"--time", "0.25"}, 0.25},                                   //
      {{"--time", "7"}, 1.0},                                       // after the last key: held
      {{"--frame", "13"}, 0.5},                                     // (13 - 1) / 24
      {{"--frame", "4", "--fps", "8", "--frame-start", "0"}, 0.5},  // 4 / 8
      {{"--time", "0.5", "--animation", "stay"}, -1.0},             // only "stay": x = -1
      {{"--time", "0.5", "--animation", "0"}, 0.5},                 // "slide" by index
  };
  for (size_t c = 0; c < cases.size(); ++c) {
    SCOPED_TRACE(c);
    const std::string out = dir + "/frame" + std::to_string(c) + ".exr";
    std::vector<std::string> args = render_args(scene, out);
    args.insert(args.end(), cases[c].args.begin(), cases[c].args.end());
    const auto result = run_kiln(args);
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    EXPECT_EQ(middle_row_alpha(out), expected_row(cases[c].t));
  }
  // The time options are recorded as numbers, and the resolved seconds with them.
  EXPECT_EQ(attribute(dir + "/frame1.exr", "kiln/time"), "double 0.5");
  EXPECT_EQ(attribute(dir + "/frame1.exr", "kiln/time_seconds"), "double 0.5");
  EXPECT_EQ(attribute(dir + "/frame4.exr", "kiln/frame"), "int 13");
  EXPECT_EQ(attribute(dir + "/frame4.exr", "kiln/time_seconds"), "double 0.5");
  EXPECT_EQ(attribute(dir + "/frame5.exr", "kiln/fps"), "double 8");
  EXPECT_EQ(attribute(dir + "/frame5.exr", "kiln/frame_start"), "int 0");
  EXPECT_EQ(attribute(dir + "/frame6.exr", "kiln/animation"), "string stay");
  EXPECT_EQ(attribute(dir + "/frame0.exr", "kiln/time"), "");  // a still records none
  // The shot's rate and first frame always (their defaults when not given); a frame's place in the
  // shot as OpenEXR's standard framesPerSecond and timeCode, counted from the first frame.
  EXPECT_EQ(attribute(dir + "/frame0.exr", "kiln/fps"), "double 24");
  EXPECT_EQ(attribute(dir + "/frame0.exr", "kiln/frame_start"), "int 1");
  EXPECT_EQ(attribute(dir + "/frame0.exr", "framesPerSecond"), "");
  EXPECT_EQ(attribute(dir + "/frame0.exr", "smpte:TimeCode"), "");
  EXPECT_EQ(attribute(dir + "/frame4.exr", "framesPerSecond"), "rational2i 24/1");
  EXPECT_EQ(attribute(dir + "/frame4.exr", "smpte:TimeCode"), "timecode 00:00:00:12");  // (13 - 1) at 24
  EXPECT_EQ(attribute(dir + "/frame5.exr", "framesPerSecond"), "rational2i 8/1");
  EXPECT_EQ(attribute(dir + "/frame5.exr", "smpte:TimeCode"), "timecode 00:00:00:04");
  // The time is a pixel setting: another time is another settings hash.
  EXPECT_NE(attribute(dir + "/frame1.exr", "kiln/settings_hash"),
            attribute(dir + "/frame2.exr", "kiln/settings_hash"));
}

TEST(posing_cli, bad_times_animations_and_keyframes_exit_2_with_one_line) {
  const std::string dir = scratch_folder("posing_errors");
  const std::string scene = sliding_quad(dir);
  const std::string broken = sliding_quad(scratch_folder("posing_errors_keys"), true);
  struct bad_case {
    std::vector<std::string> args;
    std::string scene;
    const char* says;
  };
  const std::vector<bad_case> cases = {
      {{"--time", "nan"}, scene, "--time"},
      {{"--time", "inf"}, scene, "--time"},
      {{"--time", "1", "--frame", "3"}, scene, "--time and --frame"},
      {{"--fps", "30"}, scene, "--fps"},
      {{"--frame-start", "0"}, scene, "--frame-start"},
      {{"--fps", "0", "--frame", "2"}, scene, "--fps"},
      {{"--animation", "walk"}, scene, "no animation 'walk' (animations: 0 'slide', 1 'stay'"},
      {{"--time", "0.5"}, broken, "/animations/0/samplers/0/input: keyframe times must strictly increase"},
  };
  for (const bad_case& c : cases) {
    SCOPED_TRACE(c.says);
    const std::string out = dir + "/bad.exr";
    std::vector<std::string> args = render_args(c.scene, out);
    args.insert(args.end(), c.args.begin(), c.args.end());
    const auto result = run_kiln(args);
    EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
    EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find(c.says), std::string::npos) << result.stderr_text;
  }
}

TEST(posing_cli, the_loaders_warnings_are_given_once_whichever_view_frames_the_animation) {
  const std::string dir = scratch_folder("posing_warnings");
  const std::string asset = sliding_quad(dir);  // "slide" and "stay" both drive the quad
  const std::string warning =
      "kiln: warning: animations 0 and 1 both drive translation of /nodes/0; the first wins (choose one "
      "with --animation)";
  // The file's camera, an orbit that frames poses across the animation, a look-at camera and a shot
  // (the framing and earlier frames' poses come first).
  for (const std::vector<std::string>& view :
       std::vector<std::vector<std::string>>{{"--time", "0.5"},
                                             {"--time", "0.5", "--camera-view", "front"},
                                             {"--time", "0.5", "--look-from", "0,0,5", "--look-at", "0,0,0"},
                                             {"--frames", "1-3", "--fps", "4"}}) {
    const std::string output = dir + (view[0] == "--frames" ? "/shot.####.exr" : "/still.exr");
    std::vector<std::string> args = {"render", asset, "-o", output, "--width", "8", "--height", "8"};
    args.insert(args.end(), view.begin(), view.end());
    const auto result = run_kiln(args);
    EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
    const std::vector<std::string> printed = lines(result.stderr_text);
    EXPECT_EQ(std::count(printed.begin(), printed.end(), warning), 1) << view[0] << " " << view.back() << "\n"
                                                                      << result.stderr_text;
  }
}

// The shared animated, skinned and morphed sample models render at several times through the
// CLI; the walking CesiumMan covers other pixels than its T-pose (the same fixed view).
TEST(posing_cli, shared_animated_assets_render_at_several_times) {
  const std::string assets = KILN_SHARED_ASSETS;
  if (!std::filesystem::exists(assets + "/README.md")) GTEST_SKIP() << "no sample assets at " << assets;
  const std::string dir = scratch_folder("posing_assets");
  for (const char* file :
       {"SimpleMorph/glTF/SimpleMorph.gltf", "AnimatedMorphSphere/glTF-Binary/AnimatedMorphSphere.glb",
        "MorphPrimitivesTest/glTF-Binary/MorphPrimitivesTest.glb", "SimpleSkin/glTF/SimpleSkin.gltf",
        "RiggedSimple/glTF-Binary/RiggedSimple.glb", "RiggedFigure/glTF-Binary/RiggedFigure.glb",
        "CesiumMan/glTF-Binary/CesiumMan.glb", "BrainStem/glTF-Binary/BrainStem.glb",
        "RecursiveSkeletons/glTF-Binary/RecursiveSkeletons.glb",
        "InterpolationTest/glTF-Binary/InterpolationTest.glb", "BoxAnimated/glTF-Binary/BoxAnimated.glb",
        "AnimatedCube/glTF/AnimatedCube.gltf", "AnimatedTriangle/glTF/AnimatedTriangle.gltf"})
    for (const char* time : {"0", "0.5", "1.25"}) {
      SCOPED_TRACE(std::string(file) + " at " + time);
      const std::string out = dir + "/asset.exr";
      const auto result = run_kiln({"render", assets + "/" + file, "-o", out, "--width", "24", "--height",
                                    "24", "--time", time, "-q", "--threads", "2"});
      ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
      const std::vector<float> alpha = alpha_of(out);
      EXPECT_GT(*std::max_element(alpha.begin(), alpha.end()), 0.0f);  // something is in view
    }
  const std::string man = assets + "/CesiumMan/glTF-Binary/CesiumMan.glb";
  const std::vector<std::string> view = {"--width",     "48",        "--height", "48", "--look-from",
                                         "0.3,0.9,2.6", "--look-at", "0,0.75,0", "-q"};
  std::vector<std::string> rest = {"render", man, "-o", dir + "/rest.exr", "--animation", "none"};
  std::vector<std::string> walk = {"render", man, "-o", dir + "/walk.exr", "--time", "0.5"};
  rest.insert(rest.end(), view.begin(), view.end());
  walk.insert(walk.end(), view.begin(), view.end());
  ASSERT_EQ(run_kiln(rest).exit_code, 0);
  ASSERT_EQ(run_kiln(walk).exit_code, 0);
  const std::vector<float> a = alpha_of(dir + "/rest.exr"), b = alpha_of(dir + "/walk.exr");
  ASSERT_EQ(a.size(), b.size());
  // The T-pose's outstretched arms make its widest row (first to last covered pixel) span over a
  // metre; walking, the arms hang and the widest row is the stride or the shoulders.
  const auto widest = [](const std::vector<float>& alpha) {
    int most = 0;
    for (int y = 0; y < 48; ++y) {
      int first = 48, last = -1;
      for (int x = 0; x < 48; ++x)
        if (alpha[size_t(y) * 48 + x] > 0.0f) {
          first = std::min(first, x);
          last = x;
        }
      most = std::max(most, last - first + 1);
    }
    return most;
  };
  EXPECT_LT(widest(b), widest(a) * 0.6) << widest(a) << " " << widest(b);
}

}  // namespace
}  // namespace kiln
