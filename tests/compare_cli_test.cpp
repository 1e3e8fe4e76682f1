// `kiln compare` and `kiln render --accel` end to end: exit codes, the JSON report's keys and
// values, and the mismatch mask.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::run_kiln;
using testing::scratch_folder;

const std::string demo_scene = std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf";

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(compare_cli, grid_agrees_with_embree_on_the_demo_scene) {
  const std::string folder = scratch_folder("compare");
  const std::string json = folder + "/report.json", mask = folder + "/mask.exr";
  auto result =
      run_kiln({"compare", demo_scene, "--width", "160", "--spp", "1", "--json", json, "--mask", mask, "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;

  nlohmann::json report = read_json(json);
  EXPECT_EQ(report["accel"], "grid");
  EXPECT_EQ(report["against"], "embree");
  EXPECT_EQ(report["agree"], true);
  EXPECT_EQ(report["mismatches"], 0);
  EXPECT_EQ(report["width"], 160);
  EXPECT_EQ(report["height"], 120);
  // One camera ray per pixel at 1 spp; the lit room with a mirror and glass spawns shadow,
  // reflection and refraction rays. With glass in the scene a shadow ray is traced by the
  // transmittance walk, closest hit after closest hit, so both backends answer those queries.
  EXPECT_EQ(report["rays"]["camera"]["rays"], 160 * 120);
  EXPECT_EQ(report["rays"]["camera"]["closest_hit_queries"], 160 * 120);
  EXPECT_GT(report["rays"]["shadow"]["closest_hit_queries"].get<uint64_t>(), 160u * 120u);
  EXPECT_GT(report["rays"]["reflection"]["rays"].get<uint64_t>(), 0u);
  EXPECT_GT(report["rays"]["refraction"]["rays"].get<uint64_t>(), 0u);
  for (const char* kind : {"camera", "shadow", "reflection", "refraction"}) {
    const auto& k = report["rays"][kind];
    for (const char* key :
         {"rays", "closest_hit_mismatches", "occlusion_mismatches", "ties", "edge_cases", "max_relative_dt"})
      EXPECT_TRUE(k.contains(key)) << kind << "." << key;
    EXPECT_EQ(k["closest_hit_mismatches"], 0) << kind;
    EXPECT_EQ(k["occlusion_mismatches"], 0) << kind;
    EXPECT_LT(k["max_relative_dt"].get<double>(), 1e-3) << kind;
  }
  const auto& image = report["image"];
  EXPECT_EQ(image["pixels"], 160 * 120);
  EXPECT_GE(image["rmse"].get<double>(), 0.0);
  EXPECT_LT(image["rmse"].get<double>(), 0.05);
  EXPECT_LE(image["max_difference"].get<double>(), 100.0);
  // Only pixels touched by ties or by rays starting on a surface may differ: a small fraction.
  EXPECT_LT(image["differing_pixels"].get<uint64_t>(), 160u * 120u / 50u);
  EXPECT_TRUE(report["examples"].is_array());

  auto in = OIIO::ImageInput::open(mask);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().width, 160);
  EXPECT_EQ(in->spec().height, 120);
  std::vector<float> pixels(size_t(160) * 120 * size_t(in->spec().nchannels));
  ASSERT_TRUE(in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  uint64_t flagged = 0;
  for (size_t i = 0; i < size_t(160) * 120; ++i) flagged += pixels[i * size_t(in->spec().nchannels)] > 0.5f;
  EXPECT_EQ(flagged, image["differing_pixels"].get<uint64_t>());
}

TEST(compare_cli, adaptive_grid_against_grid_and_bad_backend_names) {
  auto result = run_kiln(
      {"compare", demo_scene, "--width", "64", "--accel", "adaptive-grid", "--against", "grid", "-q"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  result = run_kiln({"compare", demo_scene, "--accel", "octree"});
  EXPECT_EQ(result.exit_code, 2);
  result = run_kiln({"render", demo_scene, "-o", "x.exr", "--accel", "bvh"});
  EXPECT_EQ(result.exit_code, 2);
}

// --grid-* reach the grid backends: the JSON report's structure sizes follow them, and the
// adaptive grid, however it is subdivided, still agrees with the uniform grid.
TEST(compare_cli, grid_options_shape_the_grids_and_keep_agreement) {
  const std::string folder = scratch_folder("compare_grid_options");
  auto structure = [&](const std::vector<std::string>& grid_arguments, nlohmann::json& report) {
    const std::string json = folder + "/report.json";
    std::vector<std::string> arguments = {
        "compare",   demo_scene, "--width", "48", "--accel", "adaptive-grid",
        "--against", "grid",     "--json",  json, "-q"};
    arguments.insert(arguments.end(), grid_arguments.begin(), grid_arguments.end());
    auto result = run_kiln(arguments);
    EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
    report = read_json(json);
    EXPECT_EQ(report["mismatches"], 0);
  };
  nlohmann::json flat, deep, fixed;
  structure({"--grid-max-depth", "0"}, flat);
  structure({"--grid-max-depth", "3", "--grid-max-items", "1"}, deep);
  structure({"--grid-resolution", "4", "--grid-max-depth", "2"}, fixed);

  // Depth 0: the adaptive grid is the uniform one, one node per grid.
  EXPECT_EQ(flat["grid_options"]["max_depth"], 0);
  EXPECT_EQ(flat["structure"]["accel"]["nodes"], flat["structure"]["against"]["nodes"]);
  EXPECT_EQ(flat["structure"]["accel"]["cells"], flat["structure"]["against"]["cells"]);
  // Depth 3 with cells of at most one item: many child nodes; the uniform grid ignores the depth.
  EXPECT_EQ(deep["grid_options"]["max_items"], 1);
  EXPECT_EQ(deep["structure"]["against"]["nodes"], flat["structure"]["against"]["nodes"]);
  EXPECT_GT(deep["structure"]["accel"]["nodes"].get<uint64_t>(),
            2 * deep["structure"]["against"]["nodes"].get<uint64_t>());
  // A fixed 4³ resolution for every grid: the uniform grids have exactly 64 cells per node.
  EXPECT_EQ(fixed["grid_options"]["resolution"], nlohmann::json::array({4, 4, 4}));
  EXPECT_EQ(fixed["structure"]["against"]["cells"].get<uint64_t>(),
            64 * fixed["structure"]["against"]["nodes"].get<uint64_t>());
  EXPECT_TRUE(fixed["structure"]["accel"].is_object());
}

TEST(compare_cli, bad_grid_options_exit_2_with_one_line) {
  const std::vector<std::vector<std::string>> bad = {
      {"--grid-max-depth", "7"},    {"--grid-max-depth", "-1"},   {"--grid-max-items", "0"},
      {"--grid-density", "0"},      {"--grid-density", "nan"},    {"--grid-resolution", "0"},
      {"--grid-resolution", "300"}, {"--grid-resolution", "2,3"}, {"--grid-resolution", "4,4,x"}};
  const std::string unused = scratch_folder("bad_grid_options") + "/unused.exr";
  for (const char* command : {"render", "compare"})
    for (const auto& option : bad) {
      std::vector<std::string> arguments = {command, demo_scene, "-q", option[0], option[1]};
      if (std::string(command) == "render") arguments.insert(arguments.end(), {"-o", unused});
      auto result = run_kiln(arguments);
      EXPECT_EQ(result.exit_code, 2) << command << " " << option[0] << " " << option[1];
      EXPECT_EQ(testing::lines(result.stderr_text).size(), 1u) << result.stderr_text;
      EXPECT_NE(result.stderr_text.find(option[0]), std::string::npos) << result.stderr_text;
    }
}

// The grid-rendered image matches the Embree-rendered one almost everywhere.
TEST(compare_cli, render_with_grid_backend_matches_embree_image) {
  const std::string folder = scratch_folder("render_accel");
  std::vector<std::vector<float>> images;
  for (const char* accel : {"embree", "grid", "adaptive-grid"}) {
    const std::string out = folder + "/" + accel + ".exr";
    auto result =
        run_kiln({"render", demo_scene, "-o", out, "--width", "96", "--accel", accel, "--float", "-q"});
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    auto in = OIIO::ImageInput::open(out);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("kiln/accelerator"), accel);
    std::vector<float> pixels(size_t(96) * 72 * 4);
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data()));
    images.push_back(pixels);
  }
  for (size_t k = 1; k < images.size(); ++k) {
    size_t close = 0;
    for (size_t i = 0; i < images[0].size(); ++i) close += std::abs(images[0][i] - images[k][i]) < 1e-3f;
    EXPECT_GT(close, images[0].size() * 98 / 100) << k;
  }
}

}  // namespace
}  // namespace kiln
