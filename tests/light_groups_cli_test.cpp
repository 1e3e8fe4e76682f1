// `--aovs lightgroups` end to end, read back as a compositor would: one RGB layer per light (the
// headlight too) plus emission and environment, named lightgroup_<name>; the layers sum to the
// beauty for every filter and for adaptive sampling (also beside the light split in one file); a
// render with one light turned off equals the full render less that light's layer, and the other
// lights' layers keep every bit; each source lands in its own group; the layers do not depend on
// threads or bands and leave the beauty's bytes alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "support/channel_exr.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using testing::gltf_builder;
using testing::run_kiln;
using testing::scratch_folder;

constexpr int size = 40;
const char* const rgb[3] = {".R", ".G", ".B"};

struct image : testing::channel_exr {
  // The layers whose name starts with lightgroup_, from their .R channels.
  std::set<std::string> groups() const {
    std::set<std::string> out;
    for (const std::string& c : spec.channelnames)
      if (c.rfind("lightgroup_", 0) == 0 && c.size() > 2 && c.substr(c.size() - 2) == ".R")
        out.insert(c.substr(0, c.size() - 2));
    return out;
  }
};

// Renders scene to dir/name at 40x40, 32-bit float colour, with the given options.
image render(const std::string& scene, const std::string& dir, const std::string& name,
             const std::vector<std::string>& extra) {
  return image{testing::render_float_exr(scene, dir + "/" + name, size, size, extra)};
}

std::string demo_scene(const std::string& name) { return std::string(KILN_SOURCE_DIR) + "/scenes/" + name; }

// The largest |Σ groups − beauty| over the image, relative to max(1, |beauty|).
float worst_group_sum_error(const image& im) {
  const std::set<std::string> groups = im.groups();
  float worst = 0.0f;
  for (size_t p = 0; p < im.count(); ++p)
    for (int c = 0; c < 3; ++c) {
      float sum = 0.0f;
      for (const std::string& g : groups) sum += im.at(p, g + rgb[c]);
      const float beauty = im.at(p, std::string(rgb[c]).substr(1));
      worst = std::max(worst, std::abs(sum - beauty) / std::max(1.0f, std::abs(beauty)));
    }
  return worst;
}

double layer_total(const image& im, const std::string& layer) {
  double total = 0.0;
  for (size_t p = 0; p < im.count(); ++p)
    for (const char* c : rgb) total += im.at(p, layer + c);
  return total;
}

// The groups are filed along the ray tree and the beauty is returned up it, and each is folded by
// the filter on its own: they agree to float rounding (1e-5 relative asserted), with the light
// split in the same file, for each filter and for adaptive sampling. Both demo scenes hold mirrors
// and glass, so light reaches the groups through reflection and refraction too.
TEST(light_groups_cli, groups_sum_to_the_beauty) {
  const std::string dir = scratch_folder("light_groups_sum");
  const std::vector<std::vector<std::string>> samplings = {
      {"--filter", "box", "--spp", "4"},
      {"--filter", "blackman-harris", "--spp", "2", "--sampler", "random"},
      {"--adaptive-threshold", "0.1", "--adaptive-depth", "2"},
  };
  const std::pair<const char*, std::set<std::string>> scenes[] = {
      {"cornell_box.gltf",
       {"lightgroup_ceiling_light", "lightgroup_fill_light", "lightgroup_emission",
        "lightgroup_environment"}},
      {"glass_showcase.gltf", {"lightgroup_sun", "lightgroup_emission", "lightgroup_environment"}},
  };
  const std::string closed_room = "cornell_box.gltf";
  for (const auto& [name, expected] : scenes)
    for (const auto& sampling : samplings) {
      std::vector<std::string> args = {"--aovs", "beauty,direct,reflection,refraction,lightgroups",
                                       "--background", "0.2,0.3,0.4"};
      args.insert(args.end(), sampling.begin(), sampling.end());
      const image im = render(demo_scene(name), dir, "groups.exr", args);
      const std::string what = std::string(name) + " " + sampling[0] + " " + sampling[1];
      EXPECT_EQ(im.groups(), expected) << what;
      const float worst = worst_group_sum_error(im);
      EXPECT_LE(worst, 1e-5f) << what;
      // Neither scene has emissive surfaces, and the Cornell box is closed: no ray leaves it.
      for (const std::string& g : expected)
        if (g != "lightgroup_emission" && !(g == "lightgroup_environment" && name == closed_room)) {
          EXPECT_GT(layer_total(im, g), 0.0) << what << " " << g;
        }
      EXPECT_TRUE(im.has("direct.R") && im.has("reflection.R")) << what;
      std::printf("%s: max relative |sum of light groups - beauty| %.3g\n", what.c_str(), worst);
    }
}

// The Cornell box with its fill light at intensity 0 equals the full render less the fill light's
// layer (1e-5 relative), and the ceiling light's layer keeps every bit: a light's share never
// depends on another light.
TEST(light_groups_cli, turning_a_light_off_subtracts_its_layer) {
  const std::string dir = scratch_folder("light_groups_off");
  for (const char* file : {"cornell_box.gltf", "cornell_box.bin", "checker.png"})
    fs::copy_file(demo_scene(file), dir + "/" + file, fs::copy_options::overwrite_existing);
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(dir + "/cornell_box.gltf"));
  bool found = false;
  for (nlohmann::json& l : doc["extensions"]["KHR_lights_punctual"]["lights"])
    if (l["name"] == "fill_light") {
      l["intensity"] = 0.0;
      found = true;
    }
  ASSERT_TRUE(found);
  std::ofstream(dir + "/fill_off.gltf") << doc.dump();
  const std::vector<std::string> args = {"--aovs", "beauty,lightgroups", "--spp", "2", "--filter", "tent"};
  const image full = render(dir + "/cornell_box.gltf", dir, "full.exr", args);
  const image off = render(dir + "/fill_off.gltf", dir, "off.exr", args);
  float worst = 0.0f;
  size_t ceiling_differing = 0;
  double fill = 0.0;
  for (size_t p = 0; p < full.count(); ++p)
    for (int c = 0; c < 3; ++c) {
      const std::string channel = std::string(rgb[c]).substr(1);
      const float expected = full.at(p, channel) - full.at(p, std::string("lightgroup_fill_light") + rgb[c]);
      worst = std::max(worst, std::abs(off.at(p, channel) - expected) / std::max(1.0f, std::abs(expected)));
      ceiling_differing += full.at(p, std::string("lightgroup_ceiling_light") + rgb[c]) !=
                           off.at(p, std::string("lightgroup_ceiling_light") + rgb[c]);
      EXPECT_EQ(off.at(p, std::string("lightgroup_fill_light") + rgb[c]), 0.0f) << p;
      fill += full.at(p, std::string("lightgroup_fill_light") + rgb[c]);
    }
  EXPECT_GT(fill, 1.0);  // the fill light lights something
  EXPECT_LE(worst, 1e-5f);
  EXPECT_EQ(ceiling_differing, 0u);
}

// Each source in its own group: an emissive quad of black metal is all emission; a mirror shows
// the background (environment); a grey quad is lit by the one light, whose group holds all of it.
// In a file without lights the headlight is lightgroup_headlight and holds everything lit.
TEST(light_groups_cli, each_source_fills_its_own_group) {
  const std::string dir = scratch_folder("light_groups_sources");
  gltf_builder b;
  const int glow = b.add_material(
      {{"emissiveFactor", {0.5, 0.25, 1.0}},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 1.0}}}});
  const int mirror = b.add_material(
      {{"pbrMetallicRoughness",
        {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 1.0}, {"roughnessFactor", 0.0}}}});
  const int grey = b.add_material(
      {{"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}});
  // Three quads facing the camera side by side: emissive (left), mirror (middle), grey (right).
  auto quad = [&](float x0, float x1, int material) {
    return b.add_node(
        {{"mesh", b.add_mesh({{x0, -0.5f, 0}, {x1, -0.5f, 0}, {x1, 0.5f, 0}, {x0, 0.5f, 0}},
                             {0, 1, 2, 0, 2, 3}, material, {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}})}});
  };
  const int nodes[3] = {quad(-1.5f, -0.55f, glow), quad(-0.45f, 0.45f, mirror), quad(0.55f, 1.5f, grey)};
  (void)nodes;
  b.add_camera({{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}});
  b.add_node({{"camera", 0}, {"translation", {0, 0, 4}}});
  const std::string unlit = dir + "/no_lights.gltf";
  b.write(unlit);
  const int lamp = b.add_light({{"type", "point"}, {"name", "lamp"}, {"intensity", 20.0}});
  b.add_node({{"name", "lamp_node"},
              {"extensions", {{"KHR_lights_punctual", {{"light", lamp}}}}},
              {"translation", {1, 0, 2}}});
  const std::string lit = dir + "/lamp.gltf";
  b.write(lit);

  const std::vector<std::string> args = {"--aovs", "beauty,lightgroups", "--background", "0.1,0.2,0.3"};
  const image im = render(lit, dir, "lamp.exr", args);
  EXPECT_EQ(im.groups(),
            (std::set<std::string>{"lightgroup_lamp", "lightgroup_emission", "lightgroup_environment"}));
  auto pixel = [](int x, int y) { return size_t(y) * size + size_t(x); };
  const size_t left = pixel(6, size / 2), middle = pixel(size / 2, size / 2),
               right = pixel(size - 7, size / 2);
  const float emission[3] = {0.5f, 0.25f, 1.0f};
  const float background[3] = {0.1f, 0.2f, 0.3f};
  for (int c = 0; c < 3; ++c) {
    // The emissive quad is black: all it shows is its emission.
    EXPECT_NEAR(im.at(left, std::string("lightgroup_emission") + rgb[c]), emission[c], 1e-6f);
    // Black metal still reflects Schlick's (1 - cos)^5 of the lamp: ~1e-8 here.
    EXPECT_LT(im.at(left, std::string("lightgroup_lamp") + rgb[c]), 1e-6f);
    // The mirror faces the camera, so it reflects the camera's side: the background, times its
    // Fresnel weight at normal incidence (F0 = base colour 1).
    EXPECT_NEAR(im.at(middle, std::string("lightgroup_environment") + rgb[c]), background[c], 1e-5f);
    // The grey quad holds the lamp's light and the background's, which lights it as an environment.
    EXPECT_GT(im.at(right, std::string("lightgroup_lamp") + rgb[c]), 0.01f);
    EXPECT_EQ(im.at(right, std::string("lightgroup_emission") + rgb[c]), 0.0f);
    EXPECT_GT(im.at(right, std::string("lightgroup_environment") + rgb[c]), 0.001f);
    EXPECT_NEAR(im.at(right, std::string("lightgroup_lamp") + rgb[c]) +
                    im.at(right, std::string("lightgroup_environment") + rgb[c]),
                im.at(right, std::string(rgb[c]).substr(1)), 1e-6f);
  }
  std::vector<std::string> headlight_args = args;
  headlight_args.insert(headlight_args.end(), {"--lighting", "headlight"});
  const image head = render(unlit, dir, "headlight.exr", headlight_args);
  EXPECT_EQ(head.groups(),
            (std::set<std::string>{"lightgroup_headlight", "lightgroup_emission", "lightgroup_environment"}));
  EXPECT_GT(head.at(right, "lightgroup_headlight.R"), 0.01f);
  EXPECT_LE(worst_group_sum_error(head), 1e-5f);
}

// Asking for light groups changes no beauty byte, and the groups do not depend on threads or bands;
// with --multipart each group is a part of its own, named like its layer.
TEST(light_groups_cli, beauty_bytes_stay_and_groups_are_deterministic) {
  const std::string dir = scratch_folder("light_groups_bytes");
  const std::string scene = demo_scene("cornell_box.gltf");
  const std::vector<std::string> base = {"--filter", "tent", "--spp", "2", "--tile-size", "6"};
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.end(), base.begin(), base.end());
    return extra;
  };
  const image plain = render(scene, dir, "plain.exr", with({"--aovs", "beauty"}));
  const image one = render(scene, dir, "one.exr", with({"--aovs", "beauty,lightgroups", "--threads", "1"}));
  const image two = render(scene, dir, "two.exr", with({"--aovs", "beauty,lightgroups", "--threads", "2"}));
  const image band = render(scene, dir, "band.exr", with({"--aovs", "beauty,lightgroups", "--band", "1/2"}));
  size_t differing = 0, thread_differing = 0, band_differing = 0;
  for (size_t p = 0; p < plain.count(); ++p) {
    for (const char* c : {"R", "G", "B", "A"}) differing += plain.at(p, c) != one.at(p, c);
    for (const std::string& g : one.groups())
      for (const char* c : rgb) {
        const std::string channel = g + c;
        thread_differing += one.at(p, channel) != two.at(p, channel);
        const size_t y = p / size_t(size);
        if (int(y) >= band.spec.y && int(y) < band.spec.y + band.spec.height)
          band_differing += one.at(p, channel) != band.at(p - size_t(band.spec.y) * size, channel);
      }
  }
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(thread_differing, 0u);
  EXPECT_EQ(band_differing, 0u);

  const auto multipart = run_kiln({"render", scene, "-o", dir + "/parts.exr", "--width", "16", "--height",
                                   "12", "-q", "--aovs", "beauty,lightgroups", "--multipart"});
  ASSERT_EQ(multipart.exit_code, 0) << multipart.stderr_text;
  const std::set<std::string> parts = testing::exr_part_names_in(dir + "/parts.exr");
  EXPECT_TRUE(parts.count("lightgroup_ceiling_light") && parts.count("lightgroup_environment"))
      << parts.size();
}

}  // namespace
}  // namespace kiln
