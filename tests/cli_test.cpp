// The command line end to end: options, exit codes, outputs, and one-line errors for bad input.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

const std::string demo_scene = std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf";

// `kiln render --help`: CLI11 prints help on stdout, captured through the shell.
std::string render_help() {
  std::string help_file = scratch_folder("help") + "/help.txt";
  std::string command = std::string("'") + KILN_BINARY + "' render --help > '" + help_file + "'";
  EXPECT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(help_file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(cli, help_documents_every_render_option) {
  auto result = run_kiln({"render", "--help"});
  EXPECT_EQ(result.exit_code, 0);
  const std::string help = render_help();
  for (const char* option : {"--output",
                             "--width",
                             "--height",
                             "--spp",
                             "--threads",
                             "--tile-size",
                             "--camera",
                             "--look-from",
                             "--look-at",
                             "--up",
                             "--fov",
                             "--scene",
                             "--float",
                             "--environment",
                             "--environment-rotation",
                             "--environment-intensity",
                             "--filter",
                             "--filter-radius",
                             "--adaptive-threshold",
                             "--adaptive-depth",
                             "--aovs",
                             "--crop"})
    EXPECT_NE(help.find(option), std::string::npos) << option;
}

TEST(cli, help_groups_the_options_by_task_output_first_limits_last) {
  std::vector<std::string> headings;
  std::map<std::string, std::string> group_of;  // option -> its heading
  std::vector<std::string> output_group;
  for (const std::string& line : lines(render_help())) {
    if (!line.empty() && line[0] != ' ' && line.back() == ':')
      headings.push_back(line.substr(0, line.size() - 1));
    if (line.rfind("  -", 0) != 0 || headings.empty()) continue;
    const std::string names = line.substr(2, line.find(' ', 2) - 2);
    group_of[names] = headings.back();
    if (headings.back() == "Output") output_group.push_back(names);
  }
  EXPECT_EQ(headings, (std::vector<std::string>{"Positionals", "Options", "Output", "Camera and scene",
                                                "Sampling", "Lighting", "AOVs", "Animation", "Render layers",
                                                "Colour", "Performance", "Progress", "Limits"}));
  ASSERT_FALSE(output_group.empty());
  EXPECT_EQ(output_group.front(), "-o,--output");
  EXPECT_EQ(group_of["-h,--help"], "Options");  // alone in CLI11's own group
  EXPECT_EQ(group_of["--spp"], "Sampling");
  EXPECT_EQ(group_of["--look-at"], "Camera and scene");
  EXPECT_EQ(group_of["--frames"], "Animation");
  EXPECT_EQ(group_of["--aovs"], "AOVs");
  EXPECT_EQ(group_of["--max-json-bytes"], "Limits");
  EXPECT_EQ(group_of["--time-limit"], "Limits");
  EXPECT_EQ(group_of["-q,--quiet"], "Progress");
  EXPECT_EQ(group_of.count("--batch-command-line"), 0u);  // internal, hidden
  // A typo as near --up (Camera, shown first) as --spp still gets the table's earlier --spp, as
  // in the Python module.
  const auto typo = run_kiln({"render", demo_scene, "-o", scratch_folder("help") + "/x.exr", "--sp", "1"});
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.stderr_text.find("unknown option --sp; did you mean --spp?"), std::string::npos)
      << typo.stderr_text;
}

TEST(cli, usage_errors_exit_2_with_one_line) {
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"render", demo_scene, "-o", "x.exr", "--no-such-option"},
           {"render", demo_scene},
           {"render", demo_scene, "-o", "x.exr", "--spp", "0"},
           {"render", demo_scene, "-o", "x.exr", "--look-from", "1,2"},
           {"render", demo_scene, "-o", "x.exr", "--width", "-5"},
           {"render", demo_scene, "-o", "x.exr", "--filter", "lanczos"},
           {"render", demo_scene, "-o", "x.exr", "--filter-radius", "0"},
           {"render", demo_scene, "-o", "x.exr", "--filter-radius", "-1"},
           {"render", demo_scene, "-o", "x.exr", "--adaptive-threshold", "-1"},
           {"render", demo_scene, "-o", "x.exr", "--adaptive-depth", "99"},
           {"render", demo_scene, "-o", "x.exr", "--adaptive-threshold", "0.1", "--spp", "4"},
           {"render", demo_scene, "-o", "x.exr", "--adaptive-threshold", "0.1", "--filter", "tent"}}) {
    auto result = run_kiln(args);
    EXPECT_EQ(result.exit_code, 2) << args.back();
    EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
  }
}

// CLI11's range checks compare with < and >, which NaN passes: every floating option refuses
// non-finite text itself, naming the option, before anything loads or renders.
TEST(cli, non_finite_floating_options_exit_2_naming_the_option) {
  const std::string out = scratch_folder("non_finite_options") + "/out.exr";
  for (const char* option :
       {"--fov", "--environment-rotation", "--environment-intensity", "--min-throughput"})
    for (const char* value : {"nan", "-nan", "inf", "-inf", "1e999"}) {
      auto result = run_kiln({"render", demo_scene, "-o", out, option, value});
      EXPECT_EQ(result.exit_code, 2) << option << ' ' << value;
      ASSERT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
      EXPECT_NE(result.stderr_text.find(option), std::string::npos) << result.stderr_text;
      EXPECT_NE(result.stderr_text.find("finite"), std::string::npos) << result.stderr_text;
    }
  auto result = run_kiln({"compare", demo_scene, "--pixel-tolerance", "nan"});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("--pixel-tolerance"), std::string::npos) << result.stderr_text;
  EXPECT_FALSE(fs::exists(out));
  // Finite values at the ends of the ranges still pass the check.
  result =
      run_kiln({"render", demo_scene, "-o", out, "--width", "8", "--height", "8", "--fov", "179",
                "--environment-rotation", "-36000", "--min-throughput", "0", "--environment-intensity", "0"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
}

// The size limit applies before the scene loads: the asset named here does not even exist.
TEST(cli, images_over_the_pixel_limit_are_refused_before_loading) {
  const std::string out = scratch_folder("pixel_limit") + "/out.exr";
  auto result =
      run_kiln({"render", "/no/such/asset.gltf", "-o", out, "--width", "65536", "--height", "65536"});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  ASSERT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("4294967296 pixels"), std::string::npos) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("--max-pixels"), std::string::npos) << result.stderr_text;
  // One side given, the other from the camera's aspect: refused once the camera is known.
  result = run_kiln({"render", demo_scene, "-o", out, "--width", "40000"});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("--max-pixels"), std::string::npos) << result.stderr_text;
  // The limit is exactly width × height and can be moved.
  result = run_kiln(
      {"render", demo_scene, "-o", out, "--width", "200", "--height", "100", "--max-pixels", "19999"});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  result = run_kiln(
      {"render", demo_scene, "-o", out, "--width", "200", "--height", "100", "--max-pixels", "20000"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
}

TEST(cli, glass_showcase_renders_with_its_environment_map) {
  const std::string scenes = std::string(KILN_SOURCE_DIR) + "/scenes/";
  std::string out = scratch_folder("showcase") + "/out.exr";
  auto result = run_kiln({"render", scenes + "glass_showcase.gltf", "-o", out, "--width", "64", "--height",
                          "48", "--environment", scenes + "glass_showcase_sky.hdr", "--environment-intensity",
                          "2", "--show-background", "--threads", "2"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("refraction rays"), std::string::npos) << result.stderr_text;
  EXPECT_EQ(result.stderr_text.find(" 0 refraction rays"), std::string::npos) << result.stderr_text;
  // Every sample of this scene is finite, and the summary and the EXR header both say so.
  EXPECT_NE(result.stderr_text.find("; 0 non-finite samples discarded)"), std::string::npos)
      << result.stderr_text;
  {
    auto in = OIIO::ImageInput::open(out);
    ASSERT_TRUE(in);
    const OIIO::ParamValue* discarded = in->spec().find_attribute("kiln/discarded_samples");
    ASSERT_NE(discarded, nullptr);
    EXPECT_EQ(discarded->type(), OIIO::TypeDesc::DOUBLE);  // a number, not text
    EXPECT_EQ(discarded->get_float(), 0.0f);
  }
  // A file OpenImageIO cannot read is bad input naming the option.
  result =
      run_kiln({"render", scenes + "glass_showcase.gltf", "-o", out, "--environment", scenes + "README.md"});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("--environment"), std::string::npos) << result.stderr_text;
  EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
}

// The header attribute `name` of an EXR file, or "" when it has none.
std::string exr_attribute(const std::string& path, const std::string& name) {
  auto in = OIIO::ImageInput::open(path);
  return in ? in->spec().get_string_attribute(name) : "";
}

TEST(cli, filter_and_adaptive_sampling_are_recorded_and_reported) {
  std::string dir = scratch_folder("filter");
  auto result = run_kiln({"render", demo_scene, "-o", dir + "/g.exr", "--width", "32", "--spp", "4",
                          "--filter", "gaussian", "--filter-radius", "1.25"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(exr_attribute(dir + "/g.exr", "kiln/filter"), "gaussian 1.25");
  EXPECT_EQ(exr_attribute(dir + "/g.exr", "kiln/adaptive"), "off");
  EXPECT_NE(result.stderr_text.find("4 spp, gaussian 1.25 filter"), std::string::npos) << result.stderr_text;
  // The default radius of the named filter.
  result = run_kiln(
      {"render", demo_scene, "-o", dir + "/b.exr", "--width", "32", "--filter", "blackman-harris", "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(exr_attribute(dir + "/b.exr", "kiln/filter"), "blackman-harris 2");
  result = run_kiln({"render", demo_scene, "-o", dir + "/a.exr", "--width", "32", "--height", "24",
                     "--adaptive-threshold", "0.05", "--adaptive-depth", "3"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(exr_attribute(dir + "/a.exr", "kiln/adaptive"), "threshold 0.05, depth 3");
  EXPECT_NE(result.stderr_text.find("adaptive threshold 0.05, depth 3"), std::string::npos)
      << result.stderr_text;
  // At least the 33×25 pixel corners, and more where edges split pixels.
  size_t at = result.stderr_text.find(" camera,");
  ASSERT_NE(at, std::string::npos) << result.stderr_text;
  size_t start = result.stderr_text.rfind('(', at);
  EXPECT_GT(std::stoull(result.stderr_text.substr(start + 1, at - start - 1)), 33ull * 25);
}

TEST(cli, impossible_camera_is_bad_input) {
  std::string out = scratch_folder("camera") + "/out.exr";
  auto result = run_kiln({"render", demo_scene, "-o", out, "--look-from", "1,1,1", "--look-at", "1,1,1"});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.stderr_text.find("same point"), std::string::npos) << result.stderr_text;
  result = run_kiln({"render", demo_scene, "-o", out, "--camera", "no_such_camera"});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.stderr_text.find("main"), std::string::npos)
      << "lists the cameras: " << result.stderr_text;
  EXPECT_FALSE(fs::exists(out));
}

TEST(cli, missing_file_is_bad_input_naming_the_file) {
  std::string out = scratch_folder("missing") + "/out.exr";
  auto result = run_kiln({"render", "/nonexistent/asset.gltf", "-o", out});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(lines(result.stderr_text).size(), 1u);
  EXPECT_NE(result.stderr_text.find("/nonexistent/asset.gltf"), std::string::npos);
}

TEST(cli, unwritable_output_is_an_io_failure_before_rendering) {
  auto result = run_kiln({"render", demo_scene, "-o", "/nonexistent_folder/out.exr"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.stderr_text.find("does not exist"), std::string::npos) << result.stderr_text;
}

TEST(cli, renders_demo_scene_to_exr_with_aovs_and_camera_aspect) {
  std::string out = scratch_folder("demo") + "/demo.exr";
  auto result = run_kiln({"render", demo_scene, "-o", out, "--width", "120", "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  auto in = OIIO::ImageInput::open(out);
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  EXPECT_EQ(spec.width, 120);
  EXPECT_EQ(spec.height, 90);  // the demo camera's aspect ratio is 4:3
  std::vector<std::string> expected = {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z"};
  EXPECT_EQ(spec.channelnames, expected);
  EXPECT_NE(spec.find_attribute("worldToCamera"), nullptr);
  EXPECT_NE(spec.find_attribute("worldToNDC"), nullptr);
  std::vector<float> pixels(size_t(spec.width) * spec.height * 8);
  ASSERT_TRUE(in->read_image(0, 0, 0, 8, OIIO::TypeDesc::FLOAT, pixels.data()));
  size_t hits = 0;
  double sum = 0.0;
  for (size_t i = 0; i < size_t(spec.width) * spec.height; ++i) {
    const float* p = &pixels[i * 8];
    for (int c = 0; c < 8; ++c)
      if (c != 4) {
        ASSERT_TRUE(std::isfinite(p[c]));
      }
    if (p[3] > 0.0f) {
      ++hits;
      EXPECT_TRUE(std::isfinite(p[4]));
      EXPECT_NEAR(std::sqrt(p[5] * p[5] + p[6] * p[6] + p[7] * p[7]), 1.0, 2e-3);
    } else {
      EXPECT_TRUE(std::isinf(p[4]));
    }
    sum += p[0] + p[1] + p[2];
  }
  EXPECT_GT(hits, size_t(spec.width) * spec.height / 2);  // the box fills most of the frame
  EXPECT_GT(sum / (spec.width * spec.height), 0.05);      // and it is lit
}

TEST(cli, float_option_writes_32_bit_colour) {
  std::string out = scratch_folder("float") + "/f.exr";
  auto result =
      run_kiln({"render", demo_scene, "-o", out, "--width", "16", "--height", "12", "--float", "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  auto in = OIIO::ImageInput::open(out);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().channelformat(0), OIIO::TypeDesc::FLOAT);
}

// Every broken file in tests/data/bad_gltf exits 2 with one line naming the file.
TEST(cli, bad_input_files_exit_2_with_one_line_naming_the_file) {
  fs::path folder = fs::path(KILN_SOURCE_DIR) / "tests" / "data" / "bad_gltf";
  size_t checked = 0;
  for (const auto& entry : fs::directory_iterator(folder)) {
    std::string ext = entry.path().extension().string();
    if (ext != ".gltf" && ext != ".glb") continue;
    std::string out = scratch_folder("bad") + "/out.exr";
    auto result = run_kiln({"render", entry.path().string(), "-o", out, "--width", "8", "--height", "8"});
    EXPECT_EQ(result.exit_code, 2) << entry.path() << ": " << result.stderr_text;
    EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find(entry.path().filename().string()), std::string::npos)
        << result.stderr_text;
    EXPECT_FALSE(fs::exists(out));
    ++checked;
  }
  EXPECT_GE(checked, 9u);
}

}  // namespace
}  // namespace kiln
