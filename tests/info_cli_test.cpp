// `kiln info` end to end: the JSON document against the values in the glTF files themselves
// (cameras, lights, variants, animations, extensions, nodes), the text form, the support status
// of an extension kiln ignores, and bad input refused with the line `kiln render` prints.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "support/run_kiln.h"

namespace kiln {
namespace {

using nlohmann::json;
using testing::run_kiln;
using testing::scratch_folder;

const std::string assets = KILN_SHARED_ASSETS;
const std::string quadric_showcase = std::string(KILN_SOURCE_DIR) + "/scenes/quadric_showcase.gltf";
constexpr double degrees_per_radian = 180.0 / 3.14159265358979323846;

// The JSON of a .gltf, or the JSON chunk of a .glb (12-byte header, then its length and type).
json gltf_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.compare(0, 4, "glTF") != 0) return json::parse(bytes);
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return json::parse(bytes.substr(20, length));
}

// kiln info --json ASSET ARGS, which must succeed.
json info_of(const std::string& asset, std::vector<std::string> arguments = {}) {
  arguments.insert(arguments.begin(), {"info", "--json", asset, "-q", "--threads", "2"});
  const testing::command_result run = run_kiln(arguments);
  EXPECT_EQ(run.exit_code, 0) << run.stderr_text;
  return json::parse(run.stdout_text);
}

void expect_lights_of_file(const json& info, const json& file) {
  const json& lights = file["extensions"]["KHR_lights_punctual"]["lights"];
  ASSERT_EQ(info["lights"].size(), lights.size());
  for (size_t i = 0; i < lights.size(); ++i) {
    const json& shown = info["lights"][i];
    EXPECT_EQ(shown["name"], lights[i].value("name", ""));
    EXPECT_EQ(shown["type"], lights[i]["type"]);
    EXPECT_DOUBLE_EQ(shown["intensity"].get<double>(), lights[i].value("intensity", 1.0));
    const json colour = lights[i].value("color", json::array({1.0, 1.0, 1.0}));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(shown["color"][c].get<double>(), colour[c].get<double>(), 1e-6);
  }
}

TEST(info_cli, json_lists_what_the_file_declares_and_estimates_the_default_render) {
  const json file = gltf_json(quadric_showcase);
  const json info = info_of(quadric_showcase);
  ASSERT_EQ(info["cameras"].size(), 1u);
  EXPECT_EQ(info["cameras"][0]["name"], "main");
  EXPECT_EQ(info["cameras"][0]["type"], "perspective");
  EXPECT_NEAR(info["cameras"][0]["yfov_degrees"].get<double>(),
              file["cameras"][0]["perspective"]["yfov"].get<double>() * degrees_per_radian, 1e-4);
  expect_lights_of_file(info, file);
  ASSERT_EQ(info["extensions"].size(), file["extensionsUsed"].size());
  for (size_t i = 0; i < file["extensionsUsed"].size(); ++i) {
    EXPECT_EQ(info["extensions"][i]["name"], file["extensionsUsed"][i]);
    EXPECT_EQ(info["extensions"][i]["support"], "supported");
    EXPECT_EQ(info["extensions"][i]["required"], false);
  }
  EXPECT_TRUE(info["animations"].empty());
  EXPECT_TRUE(info["variants"].empty());
  EXPECT_EQ(info["scene"], 0);
  EXPECT_EQ(info["scenes"][0]["nodes"], file["scenes"][0]["nodes"]);
  // Each node with a KILN_quadric places one quadric; nothing else holds geometry.
  ASSERT_EQ(info["nodes"].size(), file["nodes"].size());
  int quadric_nodes = 0;
  for (size_t i = 0; i < file["nodes"].size(); ++i) {
    const bool quadric =
        file["nodes"][i].contains("extensions") && file["nodes"][i]["extensions"].contains("KILN_quadric");
    quadric_nodes += quadric;
    EXPECT_EQ(info["nodes"][i]["quadrics"], quadric ? 1 : 0) << i;
    EXPECT_EQ(info["nodes"][i]["triangles"], 0) << i;
    EXPECT_EQ(info["nodes"][i]["name"], file["nodes"][i].value("name", ""));
  }
  EXPECT_EQ(info["geometry"]["quadrics"], quadric_nodes);
  EXPECT_GT(quadric_nodes, 5);
  // The ground disk (radius 12 about the origin) bounds the scene sideways; its top is y = 0.
  EXPECT_NEAR(info["bounds"]["min"][0].get<double>(), -12.0, 1e-9);
  EXPECT_NEAR(info["bounds"]["max"][2].get<double>(), 12.0, 1e-9);
  EXPECT_NEAR(info["bounds"]["min"][1].get<double>(), 0.0, 1e-9);
  // The default render: 640 wide at the camera's aspect ratio, 16 samples.
  const double aspect = file["cameras"][0]["perspective"]["aspectRatio"].get<double>();
  EXPECT_EQ(info["render"]["width"], 640);
  EXPECT_EQ(info["render"]["height"], int(std::lround(640 / aspect)));
  EXPECT_EQ(info["render"]["spp"], 16);
  EXPECT_GT(info["render"]["peak_memory_bytes"].get<double>(), 1e6);
  EXPECT_GT(info["render"]["render_seconds_one_thread"].get<double>(), 0.0);
  // The view options describe another render, whose estimate follows them.
  const json small = info_of(quadric_showcase, {"--width", "64", "--spp", "1"});
  EXPECT_EQ(small["render"]["width"], 64);
  EXPECT_EQ(small["render"]["spp"], 1);
  EXPECT_LT(small["render"]["peak_memory_bytes"].get<double>(),
            info["render"]["peak_memory_bytes"].get<double>());
}

TEST(info_cli, text_names_cameras_lights_and_the_node_tree) {
  const testing::command_result run = run_kiln({"info", quadric_showcase, "-q", "--threads", "2"});
  ASSERT_EQ(run.exit_code, 0) << run.stderr_text;
  const std::string& text = run.stdout_text;
  EXPECT_NE(text.find("cameras: 1 (--camera INDEX or NAME)\n  0 'main': perspective, yfov 42.9718 degrees\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("  0 'key': point, colour (1, 0.95, 0.9), intensity 150 cd\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("  KILN_quadric (used): supported\n"), std::string::npos) << text;
  EXPECT_NE(text.find("nodes of scene 0:\n"), std::string::npos) << text;
  EXPECT_NE(text.find("geometry: 0 triangles, 11 quadrics; 11 instances of 0 meshes\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("estimate: peak memory "), std::string::npos) << text;
}

TEST(info_cli, an_unknown_optional_extension_is_ignored_and_a_required_one_refused_as_render_refuses_it) {
  const std::string dir = scratch_folder("info_extensions");
  const std::string path = testing::copy_scene(dir);
  json file = gltf_json(path);
  file["extensionsUsed"].push_back("EXT_made_up");
  std::ofstream(path) << file.dump();
  const testing::command_result run = run_kiln({"info", "--json", path, "--threads", "2"});
  ASSERT_EQ(run.exit_code, 0) << run.stderr_text;
  const json info = json::parse(run.stdout_text);
  EXPECT_EQ(info["extensions"].back(),
            json({{"name", "EXT_made_up"}, {"required", false}, {"support", "ignored"}}));
  EXPECT_NE(run.stderr_text.find("warning: extension EXT_made_up is not supported; it is ignored"),
            std::string::npos)
      << run.stderr_text;
  expect_lights_of_file(info, file);

  file["extensionsRequired"] = {"EXT_made_up"};
  std::ofstream(path) << file.dump();
  const testing::command_result refused = run_kiln({"info", path});
  const testing::command_result render = run_kiln({"render", path, "-o", dir + "/x.exr"});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(render.exit_code, 2);
  EXPECT_EQ(refused.stderr_text, render.stderr_text);
  EXPECT_NE(
      refused.stderr_text.find("/extensionsRequired/0: required extension EXT_made_up is not supported"),
      std::string::npos)
      << refused.stderr_text;
  EXPECT_TRUE(refused.stdout_text.empty());
  // Options are checked as render checks them.
  const testing::command_result bad_scene = run_kiln({"info", quadric_showcase, "--scene", "3"});
  const testing::command_result render_scene =
      run_kiln({"render", quadric_showcase, "-o", dir + "/x.exr", "--scene", "3"});
  EXPECT_EQ(bad_scene.exit_code, 2);
  EXPECT_EQ(bad_scene.stderr_text, render_scene.stderr_text);
  EXPECT_FALSE(std::filesystem::exists(dir + "/x.exr"));
}

TEST(info_cli, shared_assets_cameras_variants_lights_and_animations_are_the_files) {
  const std::string cameras = assets + "/Cameras/glTF/Cameras.gltf";
  if (!std::filesystem::exists(cameras)) GTEST_SKIP() << "no sample assets";
  {
    const json file = gltf_json(cameras);
    const json info = info_of(cameras);
    ASSERT_EQ(info["cameras"].size(), 2u);
    EXPECT_EQ(info["cameras"][0]["type"], "perspective");
    EXPECT_NEAR(info["cameras"][0]["yfov_degrees"].get<double>(),
                file["cameras"][0]["perspective"]["yfov"].get<double>() * degrees_per_radian, 1e-4);
    EXPECT_EQ(info["cameras"][1]["type"], "orthographic");
    EXPECT_EQ(info["cameras"][1]["xmag"], file["cameras"][1]["orthographic"]["xmag"]);
    EXPECT_EQ(info["cameras"][1]["ymag"], file["cameras"][1]["orthographic"]["ymag"]);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(info["cameras"][0]["position"][c].get<double>(),
                  file["nodes"][1]["translation"][c].get<double>(), 1e-12);
    EXPECT_EQ(info["geometry"]["triangles"], 2);
  }
  {
    const std::string shoe = assets + "/MaterialsVariantsShoe/glTF/MaterialsVariantsShoe.gltf";
    const json file = gltf_json(shoe);
    const json info = info_of(shoe, {"--width", "32"});
    std::vector<std::string> names;
    for (const json& v : file["extensions"]["KHR_materials_variants"]["variants"]) names.push_back(v["name"]);
    EXPECT_EQ(info["variants"], json(names));
    EXPECT_EQ(names.size(), 3u);
  }
  {
    const std::string lamp = assets + "/LightsPunctualLamp/glTF/LightsPunctualLamp.gltf";
    const json info = info_of(lamp, {"--width", "32"});
    expect_lights_of_file(info, gltf_json(lamp));
    EXPECT_EQ(info["lights"].size(), 5u);
    EXPECT_EQ(info["render"]["lighting"], "file lights (5) + studio environment");
  }
  {
    const std::string car = assets + "/ToyCar/glTF/ToyCar.gltf";
    const json file = gltf_json(car);
    const json info = info_of(car, {"--width", "32"});
    ASSERT_EQ(info["cameras"].size(), file["cameras"].size());
    for (size_t i = 0; i < file["cameras"].size(); ++i) {
      EXPECT_EQ(info["cameras"][i]["name"], file["cameras"][i]["name"]);
      EXPECT_NEAR(info["cameras"][i]["yfov_degrees"].get<double>(),
                  file["cameras"][i]["perspective"]["yfov"].get<double>() * degrees_per_radian, 1e-4);
    }
    for (size_t i = 0; i < file["extensionsUsed"].size(); ++i) {
      EXPECT_EQ(info["extensions"][i]["name"], file["extensionsUsed"][i]);
      EXPECT_EQ(info["extensions"][i]["support"], "supported");
    }
    EXPECT_EQ(info["render"]["view"], file["cameras"][0]["name"]);
  }
  {
    const std::string man = assets + "/CesiumMan/glTF-Binary/CesiumMan.glb";
    const json file = gltf_json(man);
    const json info = info_of(man, {"--width", "32"});
    ASSERT_EQ(info["animations"].size(), 1u);
    EXPECT_EQ(info["animations"][0]["channels"], file["animations"][0]["channels"].size());
    // Every sampler's input accessor declares its min and max: the animation spans them all.
    double start = 1e30, end = -1e30;
    for (const json& sampler : file["animations"][0]["samplers"]) {
      const json& input = file["accessors"][sampler["input"].get<size_t>()];
      start = std::min(start, input["min"][0].get<double>());
      end = std::max(end, input["max"][0].get<double>());
    }
    EXPECT_NEAR(info["animations"][0]["start"].get<double>(), start, 1e-6);
    EXPECT_NEAR(info["animations"][0]["duration"].get<double>(), end - start, 1e-6);
    EXPECT_GT(info["geometry"]["triangles"].get<int>(), 1000);
  }
}

}  // namespace
}  // namespace kiln
