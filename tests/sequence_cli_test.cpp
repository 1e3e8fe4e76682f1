// Frame sequences end to end: `kiln render --frames` poses a sliding quad (rigid: the backend moves
// its instance) and a morphing quad (deformed: its mesh is refitted) frame after frame in one
// process; each frame covers the columns the closed form says and equals, channel for channel, the
// single-frame render of `--frame N`. Bad ranges and outputs without a frame placeholder exit 2
// with one line.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::gltf_builder;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

constexpr int side = 8;
constexpr int fps = 5;  // frame N at t = (N - 1) / 5: no quad edge meets a pixel centre

// Top half: a quad over x -1..0 sliding +1 in x from t = 0 to 1. Bottom half: a quad over
// x -1..-0.5 whose right edge a morph target moves +1.5 as its weight goes 0 -> 1 over t = 0..1.
// An orthographic camera at z = 5 sees x and y in -1..1.
std::string moving_quads(const std::string& folder) {
  gltf_builder b;
  const int slide = b.add_mesh({{-1, 0, 0}, {0, 0, 0}, {0, 1, 0}, {-1, 1, 0}}, {0, 1, 2, 0, 2, 3});
  const int slider = b.add_node({{"mesh", slide}});
  const int morph = b.add_mesh({{-1, -1, 0}, {-0.5f, -1, 0}, {-0.5f, 0, 0}, {-1, 0, 0}}, {0, 1, 2, 0, 2, 3});
  const int target =
      b.add_data(std::vector<float>{0, 0, 0, 1.5f, 0, 0, 1.5f, 0, 0, 0, 0, 0}, 5126, "VEC3", 3);
  b.doc["meshes"][morph]["primitives"][0]["targets"] = {{{"POSITION", target}}};
  b.doc["meshes"][morph]["weights"] = {0.0};
  const int morpher = b.add_node({{"mesh", morph}});
  const int camera =
      b.add_camera({{"type", "orthographic"},
                    {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 100}}}});
  b.add_node({{"camera", camera}, {"translation", {0, 0, 5}}});
  const int times = b.add_data(std::vector<float>{0, 1}, 5126, "SCALAR", 1);
  const int moves = b.add_data(std::vector<float>{0, 0, 0, 1, 0, 0}, 5126, "VEC3", 3);
  const int weights = b.add_data(std::vector<float>{0, 1}, 5126, "SCALAR", 1);
  b.doc["animations"].push_back(
      {{"samplers", {{{"input", times}, {"output", moves}}, {{"input", times}, {"output", weights}}}},
       {"channels",
        {{{"sampler", 0}, {"target", {{"node", slider}, {"path", "translation"}}}},
         {{"sampler", 1}, {"target", {{"node", morpher}, {"path", "weights"}}}}}}});
  return b.write(folder + "/quads.gltf");
}

struct exr_pixels {
  int width = 0, height = 0, channels = 0;
  std::vector<std::string> names;
  std::vector<float> values;
  std::string frame, rate, time_code;  // kiln/frame; framesPerSecond and timeCode as OpenImageIO prints them
};

exr_pixels read_exr(const std::string& path) {
  exr_pixels image;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return image;
  const OIIO::ImageSpec& spec = in->spec();
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  image.names = spec.channelnames;
  image.frame = std::to_string(spec.get_int_attribute("kiln/frame", -1));
  if (const OIIO::ParamValue* code = spec.find_attribute("smpte:TimeCode"))
    image.time_code = code->get_string();
  if (const OIIO::ParamValue* rate = spec.find_attribute("framesPerSecond")) image.rate = rate->get_string();
  image.values.resize(size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.values.data());
  return image;
}

// Alpha of row y, column by column.
std::vector<float> alpha_row(const exr_pixels& image, int y) {
  int alpha = 0;
  for (int c = 0; c < image.channels; ++c)
    if (image.names[size_t(c)] == "A") alpha = c;
  std::vector<float> row;
  for (int x = 0; x < image.width; ++x)
    row.push_back(image.values[(size_t(y) * image.width + x) * image.channels + alpha]);
  return row;
}

// Columns whose centres lie in [x0, x1].
std::vector<float> covered(double x0, double x1) {
  std::vector<float> row;
  for (int i = 0; i < side; ++i) {
    const double x = -1.0 + (i + 0.5) * 2.0 / side;
    row.push_back(x >= x0 && x <= x1 ? 1.0f : 0.0f);
  }
  return row;
}

std::vector<std::string> render_args(const std::string& scene, const std::string& out) {
  // One sample per pixel, at its centre: the closed form's coverage.
  return {"render",   scene,
          "-o",       out,
          "--width",  std::to_string(side),
          "--height", std::to_string(side),
          "--fps",    std::to_string(fps)};
}

TEST(sequence_cli, frames_move_and_deform_as_the_closed_form_says_and_equal_single_frames) {
  const std::string dir = scratch_folder("sequence_frames");
  const std::string scene = moving_quads(dir);
  std::vector<std::string> args = render_args(scene, dir + "/shot.####.exr");
  args.insert(args.end(), {"--frames", "1-5", "--aovs", "beauty,Z,N,P,id"});
  const auto sequence = run_kiln(args);
  ASSERT_EQ(sequence.exit_code, 0) << sequence.stderr_text;
  // The first frame builds the backend; every later one updates it in place.
  EXPECT_NE(sequence.stderr_text.find("kiln: frame 1: backend built"), std::string::npos)
      << sequence.stderr_text;
  for (int frame = 2; frame <= 5; ++frame)
    EXPECT_NE(sequence.stderr_text.find("kiln: frame " + std::to_string(frame) +
                                        ": instances moved and deformed meshes refitted"),
              std::string::npos)
        << sequence.stderr_text;
  for (int frame = 1; frame <= 5; ++frame) {
    SCOPED_TRACE(frame);
    char name[32];
    std::snprintf(name, sizeof name, "/shot.%04d.exr", frame);
    const exr_pixels image = read_exr(dir + name);
    ASSERT_EQ(image.width, side);
    EXPECT_EQ(image.frame, std::to_string(frame));
    EXPECT_EQ(image.rate, std::to_string(fps) + "/1");
    EXPECT_EQ(image.time_code, "00:00:00:0" + std::to_string(frame - 1));  // frame 1 is the shot's first
    const double t = double(frame - 1) / fps;
    EXPECT_EQ(alpha_row(image, 1), covered(-1.0 + t, t));                  // the slider, top half
    EXPECT_EQ(alpha_row(image, side - 2), covered(-1.0, -0.5 + 1.5 * t));  // the morph, bottom half
    // The same frame rendered on its own: every channel, every pixel.
    std::vector<std::string> single = render_args(scene, dir + "/single.exr");
    single.insert(single.end(), {"--frame", std::to_string(frame), "--aovs", "beauty,Z,N,P,id", "-q"});
    ASSERT_EQ(run_kiln(single).exit_code, 0);
    const exr_pixels alone = read_exr(dir + "/single.exr");
    EXPECT_EQ(image.names, alone.names);
    EXPECT_EQ(image.values, alone.values);
  }
}

TEST(sequence_cli, printf_patterns_steps_and_previews_name_each_frame) {
  const std::string dir = scratch_folder("sequence_patterns");
  const std::string scene = moving_quads(dir);
  std::vector<std::string> args = render_args(scene, dir + "/f_%03d.exr");
  args.insert(args.end(), {"--frames", "2-8:3", "--preview", dir + "/f_%03d.png", "-q"});
  const auto result = run_kiln(args);
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  for (const char* frame : {"002", "005", "008"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/f_" + frame + ".exr")) << frame;
    EXPECT_TRUE(std::filesystem::exists(dir + "/f_" + frame + ".png")) << frame;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/f_003.exr"));
  // One frame needs no placeholder.
  std::vector<std::string> one = render_args(scene, dir + "/one.exr");
  one.insert(one.end(), {"--frames", "4", "-q"});
  ASSERT_EQ(run_kiln(one).exit_code, 0);
  EXPECT_EQ(read_exr(dir + "/one.exr").frame, "4");
}

TEST(sequence_cli, bad_ranges_and_outputs_exit_2_with_one_line_and_write_nothing) {
  const std::string dir = scratch_folder("sequence_errors");
  const std::string scene = moving_quads(dir);
  struct bad_case {
    std::vector<std::string> args;
    std::string out;
    const char* says;
  };
  const std::vector<bad_case> cases = {
      {{"--frames", "1-3"}, "/plain.exr", "has no frame placeholder"},
      {{"--frames", "5-1"}, "/s.####.exr", "comes before the first"},
      {{"--frames", "1-9:0"}, "/s.####.exr", "the step must be at least 1"},
      {{"--frames", "one-two"}, "/s.####.exr", "expected FIRST-LAST[:STEP]"},
      {{"--frames", "1-3", "--time", "0.5"}, "/s.####.exr", "--time and --frames"},
      {{"--frames", "1-3", "--frame", "2"}, "/s.####.exr", "--frame and --frames"},
      {{"--frames", "1-3", "--preview", dir + "/p.png"}, "/s.####.exr", "--preview"},
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

// A manifest job with frames is one job per frame: each its own output (the default name gains
// .####), plan entry and resume state, and each frame the pixels of `kiln render --frame N`.
// A still scene of quadrics: each frame updates the backend built for the first in place, and its
// quadrics' intersection callbacks must read this frame's definitions, not the last frame's (freed
// with that frame's scene: AddressSanitizer's heap-use-after-free before the fix).
TEST(sequence_cli, a_sequence_of_quadrics_updates_its_backend_from_each_frames_scene) {
  const std::string dir = scratch_folder("sequence_quadrics");
  const std::string scene = std::string(KILN_SOURCE_DIR) + "/scenes/quadric_showcase.gltf";
  std::vector<std::string> args = render_args(scene, dir + "/q.####.exr");
  args.insert(args.end(), {"--frames", "1-3", "-q"});
  const auto result = run_kiln(args);
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  std::vector<std::string> single = render_args(scene, dir + "/single.exr");
  single.insert(single.end(), {"--frame", "3", "-q"});
  ASSERT_EQ(run_kiln(single).exit_code, 0);
  EXPECT_EQ(read_exr(dir + "/q.0003.exr").values, read_exr(dir + "/single.exr").values);
}

TEST(sequence_cli, a_batch_job_with_frames_plans_renders_and_resumes_each_frame) {
  const std::string dir = scratch_folder("sequence_batch");
  const std::string scene = moving_quads(dir);
  std::ofstream(dir + "/jobs.json") << nlohmann::json(
      {{"jobs", {{{"asset", scene}, {"frames", "1-3"}, {"fps", fps}, {"resolution", "8x8"}}}}});
  const std::vector<std::string> batch = {
      "batch",     "--manifest",          dir + "/jobs.json", "--out-dir", dir + "/out",
      "--summary", dir + "/summary.json", "--resume",         "-q",        "--spp",
      "1"};
  std::vector<std::string> plan = batch;
  plan.insert(plan.end(), {"--plan-only", dir + "/plan.json"});
  const auto planning = run_kiln(plan);
  ASSERT_EQ(planning.exit_code, 0) << planning.stderr_text;
  const nlohmann::json planned = nlohmann::json::parse(std::ifstream(dir + "/plan.json"));
  ASSERT_EQ(planned["jobs"].size(), 3u) << planned.dump(1);
  EXPECT_EQ(planned["jobs"][1]["output"], dir + "/out/quads.0002.exr");
  const auto statuses = [&] {
    std::vector<std::string> out;
    const nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir + "/summary.json"));
    for (const auto& job : summary["jobs"]) out.push_back(job["status"]);
    return out;
  };
  const auto first = run_kiln(batch);
  ASSERT_EQ(first.exit_code, 0) << first.stderr_text;
  EXPECT_EQ(statuses(), (std::vector<std::string>{"rendered", "rendered", "rendered"}));
  ASSERT_EQ(run_kiln(batch).exit_code, 0);
  EXPECT_EQ(statuses(), (std::vector<std::string>{"skipped", "skipped", "skipped"}));
  std::vector<std::string> single = render_args(scene, dir + "/single.exr");
  single.insert(single.end(), {"--frame", "2", "-q"});
  ASSERT_EQ(run_kiln(single).exit_code, 0);
  const exr_pixels batch_frame = read_exr(dir + "/out/quads.0002.exr"), alone = read_exr(dir + "/single.exr");
  EXPECT_EQ(batch_frame.frame, "2");
  EXPECT_EQ(batch_frame.values, alone.values);
}

}  // namespace
}  // namespace kiln
