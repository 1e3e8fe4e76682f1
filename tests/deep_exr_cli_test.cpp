// Deep EXR output (--deep) end to end, read back with OpenEXR's DeepScanLineInputFile as a
// compositor would: a BLEND triangle half over an opaque quad, half over nothing. Sample counts
// (one per opaque interior pixel, two under the BLEND surface, none for background), samples
// sorted front to back, a front-to-back `over` flatten equal to the flat beauty, the
// deepImageState the file claims, the refusals of the paths deep output does not take, and the
// deep samples charged to --max-memory; batch jobs with their deep files.
#include <OpenEXR/ImfDeepImageStateAttribute.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/channel_exr.h"
#include "support/deep_exr.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

constexpr int size = 48;  // pixels a side

// A BLEND triangle (alpha 0.5, z = 0.5) reaching past an opaque quad (z = 0) into the background,
// both facing a camera at z = 4, with a point light.
std::string write_scene(const std::string& path, bool with_veil = true, bool with_quad = true) {
  testing::gltf_builder b;
  const int glass = b.add_material(
      {{"name", "veil"},
       {"alphaMode", "BLEND"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0.2, 0.1, 0.5}}, {"metallicFactor", 0.0}}}});
  const int blue = b.add_material(
      {{"name", "blue"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.3, 1, 1}}, {"metallicFactor", 0.0}}}});
  const std::vector<std::array<float, 3>> facing = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  if (with_veil)
    b.add_node({{"name", "veil"},
                {"mesh", b.add_mesh({{-1.6f, -1.0f, 0.5f}, {0.6f, -0.8f, 0.5f}, {-0.6f, 1.0f, 0.5f}},
                                    {0, 1, 2}, glass, {facing[0], facing[1], facing[2]})}});
  if (with_quad)
    b.add_node({{"name", "quad"},
                {"mesh", b.add_mesh({{-0.8f, -0.8f, 0}, {1.0f, -0.8f, 0}, {1.0f, 1.0f, 0}, {-0.8f, 1.0f, 0}},
                                    {0, 1, 2, 0, 2, 3}, blue, facing)}});
  b.add_lamp_and_camera({1.0, 0.8, 2.0}, 12.0, {0, 0, 4}, 0.8);
  b.write(path);
  return path;
}

// kiln render at size × size, quiet, float, with the id AOV and extra options.
testing::command_result run(const std::string& scene, const std::string& out,
                            std::vector<std::string> extra) {
  std::vector<std::string> args = {"render",   scene,
                                   "-o",       out,
                                   "--width",  std::to_string(size),
                                   "--height", std::to_string(size),
                                   "-q",       "--float",
                                   "--aovs",   "beauty,Z,id"};
  args.insert(args.end(), extra.begin(), extra.end());
  return testing::run_kiln(args);
}

testing::channel_exr render(const std::string& scene, const std::string& out,
                            const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"--aovs", "beauty,Z,id", "--spp", "16"};
  args.insert(args.end(), extra.begin(), extra.end());
  return testing::render_float_exr(scene, out, size, size, args);
}

const char* const rgba[4] = {"R", "G", "B", "A"};

// The tolerance of the flatten against the flat beauty: the over-form division and the
// compositor's products round in float, on values of order 1 (checked relative to max(1, |v|)).
constexpr float flatten_tolerance = 1e-5f;

TEST(deep_exr_cli, samples_are_sorted_counted_and_flatten_to_the_beauty) {
  const std::string dir = testing::scratch_folder("deep_exr");
  const std::string scene = write_scene(dir + "/scene.gltf");
  const testing::channel_exr flat = render(scene, dir + "/shot.exr", {"--deep"});
  // Which pixels each surface covers whole: renders of scenes with each alone (alpha 0.5 where
  // every sample hit the veil, 1 where every sample hit the quad).
  const std::string veil_scene = write_scene(dir + "/veil.gltf", true, false);
  const std::string quad_scene = write_scene(dir + "/quad.gltf", false, true);
  const testing::channel_exr veil = render(veil_scene, dir + "/veil.exr", {});
  const testing::channel_exr quad = render(quad_scene, dir + "/quad.exr", {});
  const testing::deep_file deep = testing::read_deep(dir + "/shot.deep.exr");
  ASSERT_EQ(deep.width, size);
  ASSERT_EQ(deep.height, size);
  for (const char* name :
       {"R", "G", "B", "A", "Z", "ZBack", "id.object", "id.material", "id.instance", "id.crypto_object"})
    EXPECT_NE(std::find(deep.names.begin(), deep.names.end(), name), deep.names.end()) << name;
  // Two surfaces at distinct depths, each merged to one sample a pixel: sorted and non-overlapping.
  EXPECT_TRUE(deep.has_state);
  EXPECT_EQ(deep.state, Imf::DIS_TIDY);

  size_t background = 0, opaque = 0, veiled = 0, over_nothing = 0, edges = 0;
  float worst = 0.0f;
  for (size_t p = 0; p < deep.counts.size(); ++p) {
    const unsigned int n = deep.counts[p];
    // Front to back: each sample's front at or behind the previous one's back.
    for (unsigned int k = 0; k < n; ++k) {
      EXPECT_LE(deep.at(p, k, "Z"), deep.at(p, k, "ZBack")) << "pixel " << p;
      if (k > 0) {
        EXPECT_LE(deep.at(p, k - 1, "ZBack"), deep.at(p, k, "Z")) << "pixel " << p;
      }
    }
    // Flatten as a compositor does: C += T·c, T *= 1 - a, front to back.
    float flattened[4] = {0, 0, 0, 0}, transmittance = 1.0f;
    for (unsigned int k = 0; k < n; ++k) {
      for (int c = 0; c < 4; ++c) flattened[c] += transmittance * deep.at(p, k, rgba[c]);
      transmittance *= 1.0f - deep.at(p, k, "A");
    }
    for (int c = 0; c < 4; ++c) {
      const float want = flat.at(p, rgba[c]);
      worst = std::max(worst, std::abs(flattened[c] - want) / std::max(1.0f, std::abs(want)));
    }
    // Whole pixels: the renders of each surface alone say what covers all of it.
    const bool whole_veil = veil.at(p, "A") == 0.5f, no_veil = veil.at(p, "A") == 0.0f;
    const bool whole_quad = quad.at(p, "A") == 1.0f, no_quad = quad.at(p, "A") == 0.0f;
    if (no_veil && no_quad) {
      ++background;
      EXPECT_EQ(n, 0u) << "background pixel " << p;
    } else if (no_veil && whole_quad) {
      ++opaque;  // the quad alone, nothing in front: N samples merged into one
      EXPECT_EQ(n, 1u) << "quad pixel " << p;
      if (n == 1) {
        EXPECT_EQ(deep.at(p, 0, "A"), 1.0f);
      }
    } else if (whole_veil && whole_quad) {
      ++veiled;  // the BLEND surface over the quad: its own sample in front
      ASSERT_EQ(n, 2u) << "veiled pixel " << p;
      EXPECT_NEAR(deep.at(p, 0, "A"), 0.5f, 1e-6f) << "pixel " << p;
      EXPECT_EQ(deep.at(p, 0, "id.instance"), 0.0f);
      EXPECT_EQ(deep.at(p, 1, "id.instance"), 1.0f);
      EXPECT_NEAR(deep.at(p, 1, "A"), 1.0f, 1e-6f);  // opaque behind, in over-form
      EXPECT_LT(deep.at(p, 0, "ZBack"), deep.at(p, 1, "Z"));
    } else if (whole_veil && no_quad) {
      ++over_nothing;  // the BLEND surface over the background: one sample, its own alpha
      ASSERT_EQ(n, 1u) << "pixel " << p;
      EXPECT_NEAR(deep.at(p, 0, "A"), 0.5f, 1e-6f) << "pixel " << p;
    } else {
      ++edges;
    }
  }
  EXPECT_LE(worst, flatten_tolerance);
  // The scene has all five kinds, and edges are few.
  EXPECT_GT(background, 100u);
  EXPECT_GT(opaque, 100u);
  EXPECT_GT(veiled, 100u);
  EXPECT_GT(over_nothing, 50u);
  EXPECT_GT(edges, 0u);
  EXPECT_LT(edges, size_t(size) * size / 4);
}

TEST(deep_exr_cli, only_with_deep_is_a_deep_file_written) {
  const std::string dir = testing::scratch_folder("deep_exr_absent");
  const std::string scene = write_scene(dir + "/scene.gltf");
  render(scene, dir + "/flat.exr", {});
  EXPECT_TRUE(std::filesystem::exists(dir + "/flat.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/flat.deep.exr"));
}

// The paths deep output does not take are refused before anything renders, exit 2, one line
// naming --deep, and nothing is written.
TEST(deep_exr_cli, refuses_what_it_cannot_write_truthfully) {
  const std::string dir = testing::scratch_folder("deep_exr_refused");
  const std::string scene = write_scene(dir + "/scene.gltf");
  const std::vector<std::vector<std::string>> refused = {{"--crop", "0,0,8,8"},
                                                         {"--band", "1/4"},
                                                         {"--adaptive-threshold", "0.1"},
                                                         {"--filter", "tent"},
                                                         {"--show-background"}};
  for (std::vector<std::string> extra : refused) {
    extra.push_back("--deep");
    const auto result = run(scene, dir + "/refused.exr", extra);
    EXPECT_EQ(result.exit_code, 2) << extra[0];
    EXPECT_NE(result.stderr_text.find("--deep"), std::string::npos) << extra[0] << ": " << result.stderr_text;
    EXPECT_EQ(testing::lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_FALSE(std::filesystem::exists(dir + "/refused.exr")) << extra[0];
    EXPECT_FALSE(std::filesystem::exists(dir + "/refused.deep.exr")) << extra[0];
  }
}

// The deep samples are charged to --max-memory as tiles finish: a budget the flat render fits in
// but its deep samples (about 40 bytes a pixel here) do not stops the render, exit 2, one line,
// nothing written.
TEST(deep_exr_cli, deep_samples_are_charged_to_the_memory_budget) {
  const std::string dir = testing::scratch_folder("deep_exr_memory");
  const std::string scene = testing::copy_scene(dir);
  const std::vector<std::string> args = {"render",   scene, "-o", dir + "/room.exr", "--width", "640",
                                         "--height", "480", "-q", "--max-memory",    "30M"};
  const auto flat = testing::run_kiln(args);
  ASSERT_EQ(flat.exit_code, 0) << flat.stderr_text;
  std::filesystem::remove(dir + "/room.exr");
  std::vector<std::string> deep_args = args;
  deep_args.push_back("--deep");
  const auto deep = testing::run_kiln(deep_args);
  EXPECT_EQ(deep.exit_code, 2);
  EXPECT_NE(deep.stderr_text.find("the deep samples need about"), std::string::npos) << deep.stderr_text;
  EXPECT_EQ(testing::lines(deep.stderr_text).size(), 1u) << deep.stderr_text;
  EXPECT_FALSE(std::filesystem::exists(dir + "/room.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/room.deep.exr"));
}

// A batch job takes --deep from its manifest overrides, and no other job may write its deep file.
TEST(deep_exr_cli, batch_jobs_write_their_deep_files_and_never_one_another_s) {
  const std::string dir = testing::scratch_folder("deep_exr_batch");
  const std::string scene = write_scene(dir + "/scene.gltf");
  const auto job = [&](const std::string& output, bool deep) {
    return std::string("{\"asset\": \"") + scene + "\", \"resolution\": \"16x16\", \"output\": \"" + output +
           "\"" + (deep ? ", \"overrides\": {\"deep\": true}" : "") + "}";
  };
  std::ofstream(dir + "/ok.json") << "{\"jobs\": [" << job("a.exr", true) << ", " << job("b.exr", false)
                                  << "]}";
  const auto ok =
      testing::run_kiln({"batch", "--manifest", dir + "/ok.json", "--out-dir", dir + "/ok", "-q"});
  ASSERT_EQ(ok.exit_code, 0) << ok.stderr_text;
  EXPECT_TRUE(std::filesystem::exists(dir + "/ok/a.deep.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/ok/b.deep.exr"));
  std::ofstream(dir + "/clash.json") << "{\"jobs\": [" << job("a.exr", true) << ", "
                                     << job("a.deep.exr", false) << "]}";
  const auto clash =
      testing::run_kiln({"batch", "--manifest", dir + "/clash.json", "--out-dir", dir + "/clash", "-q"});
  EXPECT_EQ(clash.exit_code, 2);
  EXPECT_NE(clash.stderr_text.find("a.deep.exr, as does"), std::string::npos) << clash.stderr_text;
  EXPECT_FALSE(std::filesystem::exists(dir + "/clash/a.exr"));
}

}  // namespace
}  // namespace kiln
