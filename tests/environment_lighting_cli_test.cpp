// The environment as a light, end to end through the kiln binary: a sphere resting on a ground quad,
// in a file without lights, lit by kiln's studio environment (the default) or a constant one. Its
// light reaches the outputs a punctual light's does (light groups summing to the beauty, the
// diffuse and specular passes summing to the direct light, a shadow matte under the sphere); the
// image is the same bytes for any thread count and tile size; noise falls with --spp; the EXR says
// what lit it; and bad lighting options are refused with one line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>

#include "support/channel_exr.h"
#include "support/exr_header.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::channel_exr;
using testing::run_kiln;

constexpr int size = 32;
const char* const rgb[3] = {".R", ".G", ".B"};

// A grey ground quad at y = 0 and a unit sphere resting on it (rough dielectrics), no lights, seen
// from the front and above.
std::string sphere_on_ground(const std::string& dir) {
  testing::gltf_builder b;
  const int grey = b.add_material(
      {{"pbrMetallicRoughness",
        {{"baseColorFactor", {0.6, 0.6, 0.6, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.8}}}});
  const int red = b.add_material(
      {{"pbrMetallicRoughness",
        {{"baseColorFactor", {0.8, 0.2, 0.1, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.4}}}});
  b.add_node({{"mesh", b.add_mesh({{-4, 0, -4}, {4, 0, -4}, {4, 0, 4}, {-4, 0, 4}}, {0, 2, 1, 0, 3, 2}, grey,
                                  {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}})}});
  b.doc["extensionsUsed"].push_back("KILN_quadric");
  b.doc["extensions"]["KILN_quadric"]["primitives"] = {{{"kind", "sphere"}, {"radius", 1.0}}};
  b.add_node({{"translation", {0, 1, 0}},
              {"extensions", {{"KILN_quadric", {{"primitive", 0}, {"material", red}}}}}});
  b.add_camera({{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.1}}}});
  // At (0, 3, 6) looking down at (0, 0.5, 0): rotated about +X by atan2(2.5, 6).
  const double angle = -std::atan2(2.5, 6.0);
  b.add_node({{"camera", 0},
              {"translation", {0, 3, 6}},
              {"rotation", {std::sin(angle / 2), 0.0, 0.0, std::cos(angle / 2)}}});
  return b.write(dir + "/sphere_on_ground.gltf");
}

size_t pixel(int x, int y) { return size_t(y) * size + size_t(x); }

double channel_total(const channel_exr& im, const std::string& channel) {
  double total = 0.0;
  for (size_t p = 0; p < im.count(); ++p) total += im.at(p, channel);
  return total;
}

TEST(environment_lighting_cli, its_light_reaches_groups_passes_and_the_shadow_matte) {
  const std::string dir = testing::scratch_folder("environment_passes");
  const std::string scene = sphere_on_ground(dir);
  const channel_exr im = testing::render_float_exr(
      scene, dir + "/passes.exr", size, size,
      {"--spp", "4", "--aovs", "beauty,direct,lightgroups,diffuse,specular,shadow"});
  // No lights, no emission: the environment's group holds the whole beauty.
  EXPECT_FALSE(im.has("lightgroup_headlight.R"));
  float worst_sum = 0.0f, worst_direct = 0.0f;
  for (size_t p = 0; p < im.count(); ++p)
    for (const char* c : rgb) {
      const float beauty = im.at(p, std::string(c).substr(1));
      const float groups = im.at(p, std::string("lightgroup_environment") + c) +
                           im.at(p, std::string("lightgroup_emission") + c);
      worst_sum = std::max(worst_sum, std::abs(groups - beauty) / std::max(1.0f, beauty));
      const float passes = im.at(p, std::string("diffuse") + c) + im.at(p, std::string("specular") + c);
      const float direct = im.at(p, std::string("direct") + c);
      worst_direct = std::max(worst_direct, std::abs(passes - direct) / std::max(1.0f, direct));
    }
  EXPECT_LE(worst_sum, 1e-5f);
  EXPECT_LE(worst_direct, 1e-5f);
  EXPECT_GT(channel_total(im, "lightgroup_environment.G"), 1.0);
  EXPECT_GT(channel_total(im, "diffuse.R"), channel_total(im, "specular.R"));
  EXPECT_GT(channel_total(im, "specular.R"), 0.0);
  // The matte: the ground right below the sphere's silhouette is occluded from much of the sky, the
  // ground at the image's bottom corner hardly at all.
  float under = 0.0f;
  for (int x = 12; x < 20; ++x) under = std::max(under, im.at(pixel(x, 24), "shadow_environment.A"));
  const float open = im.at(pixel(1, size - 1), "shadow_environment.A");
  EXPECT_GT(under, 0.2f);
  EXPECT_LT(open, 0.1f);
  EXPECT_GT(under, 3.0f * open);
  for (size_t p = 0; p < im.count(); ++p) {
    const float m = im.at(p, "shadow_environment.A");
    ASSERT_TRUE(m >= 0.0f && m <= 1.0f) << p << ": " << m;
  }
}

TEST(environment_lighting_cli, same_bytes_for_any_thread_count_and_tile_size) {
  const std::string dir = testing::scratch_folder("environment_determinism");
  const std::string scene = sphere_on_ground(dir);
  const std::vector<std::string> base = {"--spp", "4", "--aovs", "beauty,lightgroups,shadow"};
  auto with = [&base](std::vector<std::string> extra) {
    extra.insert(extra.begin(), base.begin(), base.end());
    return extra;
  };
  const channel_exr one =
      testing::render_float_exr(scene, dir + "/one.exr", size, size, with({"--threads", "1"}));
  const channel_exr two = testing::render_float_exr(scene, dir + "/two.exr", size, size,
                                                    with({"--threads", "2", "--tile-size", "5"}));
  ASSERT_EQ(one.pixels.size(), two.pixels.size());
  EXPECT_TRUE(one.pixels == two.pixels);
  // A band is the same pixels as those rows of the whole frame.
  const channel_exr band =
      testing::render_float_exr(scene, dir + "/band.exr", size, size, with({"--band", "1/2"}));
  const size_t channels = size_t(one.spec.nchannels), row = size_t(size) * channels;
  ASSERT_EQ(band.pixels.size(), row * size / 2);
  EXPECT_TRUE(std::equal(band.pixels.begin(), band.pixels.end(), one.pixels.begin() + row * size / 2));
}

TEST(environment_lighting_cli, noise_falls_with_samples_per_pixel) {
  const std::string dir = testing::scratch_folder("environment_noise");
  const std::string scene = sphere_on_ground(dir);
  const channel_exr reference =
      testing::render_float_exr(scene, dir + "/ref.exr", size, size, {"--spp", "256", "--aovs", "beauty"});
  double previous = 1e30;
  for (const char* spp : {"1", "4", "16"}) {
    const channel_exr im = testing::render_float_exr(scene, dir + "/spp" + std::string(spp) + ".exr", size,
                                                     size, {"--spp", spp, "--aovs", "beauty"});
    double squared = 0.0;
    for (size_t p = 0; p < im.count(); ++p)
      for (const char* c : {"R", "G", "B"}) squared += std::pow(im.at(p, c) - reference.at(p, c), 2.0);
    const double rmse = std::sqrt(squared / double(im.count() * 3));
    // Each fourfold of samples should about halve the error; at least a third off is required.
    EXPECT_LT(rmse, previous * 0.67) << spp << " spp";
    previous = rmse;
  }
}

TEST(environment_lighting_cli, the_exr_records_what_lit_it) {
  const std::string dir = testing::scratch_folder("environment_record");
  const std::string scene = sphere_on_ground(dir);
  const channel_exr studio =
      testing::render_float_exr(scene, dir + "/studio.exr", 8, 8, {"--environment-samples", "3"});
  EXPECT_EQ(studio.spec.get_string_attribute("kiln/lighting"), "studio environment");
  EXPECT_EQ(studio.spec.get_string_attribute("kiln/lighting_mode"), "auto");
  EXPECT_EQ(studio.spec.get_int_attribute("kiln/environment_samples"), 3);
  const channel_exr grey =
      testing::render_float_exr(scene, dir + "/grey.exr", 8, 8, {"--background", "0.5,0.5,0.5"});
  EXPECT_EQ(grey.spec.get_string_attribute("kiln/lighting"), "background colour");
  const channel_exr head =
      testing::render_float_exr(scene, dir + "/head.exr", 8, 8, {"--lighting", "headlight"});
  EXPECT_EQ(head.spec.get_string_attribute("kiln/lighting"), "headlight");
}

// The binary as a user runs it, without the tests' --spp 1 (support/run_kiln.h): 16 samples per pixel,
// two environment sample pairs per shading point, the studio environment.
TEST(environment_lighting_cli, the_default_render_is_anti_aliased_and_lit_by_the_studio) {
  const std::string dir = testing::scratch_folder("environment_default");
  const std::string scene = sphere_on_ground(dir), out = dir + "/default.exr";
  const std::string command = std::string("'") + KILN_BINARY + "' render '" + scene + "' -o '" + out +
                              "' --width 16 --height 16 -q </dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const channel_exr im{testing::read_float_exr(out)};
  EXPECT_EQ(im.spec.get_int_attribute("samplesPerPixel"), 16);
  EXPECT_EQ(im.spec.get_int_attribute("kiln/samples_per_pixel"), 16);
  EXPECT_EQ(im.spec.get_int_attribute("kiln/environment_samples"), 2);
  EXPECT_EQ(im.spec.get_string_attribute("kiln/lighting"), "studio environment");
  // Anti-aliased: the sphere's silhouette has pixels it covers only in part.
  int partial = 0;
  for (size_t p = 0; p < im.count(); ++p) partial += im.at(p, "A") > 0.05f && im.at(p, "A") < 0.95f;
  EXPECT_GT(partial, 0);
}

TEST(environment_lighting_cli, bad_lighting_input_is_one_line_and_exit_2) {
  const std::string dir = testing::scratch_folder("environment_bad");
  const std::string scene = sphere_on_ground(dir);
  std::ofstream(dir + "/not_an_image.exr") << "this is not an image";
  std::ofstream(dir + "/empty.hdr");
  // A map claiming 10⁵ × 10⁵ texels (more than 2^27): refused from its header, nothing allocated.
  std::ofstream(dir + "/enormous.exr", std::ios::binary) << testing::exr_header_claiming(100000, 100000);
  const std::vector<std::vector<std::string>> cases = {
      {"--environment", dir + "/not_an_image.exr"},
      {"--environment", dir + "/empty.hdr"},
      {"--environment", dir + "/missing.exr"},
      {"--environment", dir + "/enormous.exr"},
      {"--environment-samples", "0"},
      {"--environment-samples", "5000"},
      {"--lighting", "sunny"},
      {"--lighting", "studio", "--background", "1,1,1"},
  };
  for (const auto& extra : cases) {
    std::vector<std::string> args = {"render", scene, "-o", dir + "/x.exr", "--width", "8", "--height", "8"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto result = run_kiln(args);
    EXPECT_EQ(result.exit_code, 2) << extra[0] << " " << extra[1] << ": " << result.stderr_text;
    EXPECT_EQ(std::count(result.stderr_text.begin(), result.stderr_text.end(), '\n'), 1)
        << result.stderr_text;
    if (extra[1].find("enormous") != std::string::npos)
      EXPECT_NE(result.stderr_text.find("more than the largest environment map"), std::string::npos);
  }
}

}  // namespace
}  // namespace kiln
