// Holdouts and render layers end to end (--holdout, --only, --holdout-invisible), read back as a
// compositor would: two layers of disjoint node sets added with `plus` equal the full render on
// every pixel (tests/render_layers_cli_test.cpp has deep layers, glass and BLEND), a holdout cuts
// alpha to zero and hides what is behind it but still casts its shadow, an invisible holdout casts
// none, and a pattern that matches no node is refused naming the nodes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/float_exr.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::gltf_builder;
using testing::run_kiln;
using testing::scratch_folder;

constexpr int size = 48;

struct image : testing::float_exr {
  float at(size_t pixel, const std::string& channel) const {
    const int c = spec.channelindex(channel);
    EXPECT_GE(c, 0) << channel;
    return c < 0 ? NAN : pixels[pixel * size_t(spec.nchannels) + size_t(c)];
  }
  size_t count() const { return spec.image_pixels(); }
};

// A red triangle in front (z = 0.5) of a blue quad (z = 0), both facing a camera at z = 4, lit by
// a point light up and to the right so the triangle's shadow falls on the quad beside it.
std::string write_scene(const std::string& path, bool with_triangle = true) {
  gltf_builder b;
  const int red = b.add_material(
      {{"name", "red"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0.1, 0.1, 1}}, {"metallicFactor", 0.0}}}});
  const int blue = b.add_material(
      {{"name", "blue"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.3, 1, 1}}, {"metallicFactor", 0.0}}}});
  const std::vector<std::array<float, 3>> facing = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  if (with_triangle)
    b.add_node({{"name", "front_triangle"},
                {"mesh", b.add_mesh({{-0.9f, -0.7f, 0.5f}, {0.4f, -0.5f, 0.5f}, {-0.4f, 0.6f, 0.5f}},
                                    {0, 1, 2}, red, {facing[0], facing[1], facing[2]})}});
  b.add_node({{"name", "back_quad"},
              {"mesh", b.add_mesh({{-1.2f, -1.2f, 0}, {1.2f, -1.2f, 0}, {1.2f, 1.2f, 0}, {-1.2f, 1.2f, 0}},
                                  {0, 1, 2, 0, 2, 3}, blue, facing)}});
  b.add_lamp_and_camera({1.0, 0.8, 2.0}, 12.0, {0, 0, 4}, 0.8);
  b.write(path);
  return path;
}

image render(const std::string& scene, const std::string& dir, const std::string& name,
             std::vector<std::string> extra) {
  std::vector<std::string> args = {"render",     scene,
                                   "-o",         dir + "/" + name,
                                   "--width",    std::to_string(size),
                                   "--height",   std::to_string(size),
                                   "-q",         "--float",
                                   "--lighting", "file"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto result = run_kiln(args);
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  return image{testing::read_float_exr(dir + "/" + name)};
}

const char* const rgba[4] = {"R", "G", "B", "A"};

// A plus B, channel c of pixel p (premultiplied): what docs/output.md says disjoint flat layers give.
float plus(const image& a, const image& b, size_t p, const char* c) { return a.at(p, c) + b.at(p, c); }

// Every camera sample lands in exactly one of two layers of disjoint node sets, so adding them is the
// full render to float rounding on every pixel, edges included, whatever the filter: the back layer
// holds the triangle's shadow (a holdout casts it) and nothing of the triangle.
TEST(holdout_cli, layers_add_into_the_full_render) {
  const std::string dir = scratch_folder("holdout_layers");
  const std::string scene = write_scene(dir + "/scene.gltf");
  for (const std::vector<std::string>& sampling :
       {std::vector<std::string>{"--spp", "1"}, std::vector<std::string>{"--spp", "4", "--filter", "tent"}}) {
    const image full = render(scene, dir, "full.exr", sampling);
    std::vector<std::string> front_args = sampling, back_args = sampling;
    front_args.insert(front_args.end(), {"--only", "front_triangle"});
    back_args.insert(back_args.end(), {"--only", "back_*"});
    const image front = render(scene, dir, "front.exr", front_args);
    const image back = render(scene, dir, "back.exr", back_args);
    size_t edges = 0, covered = 0, shadowed = 0;
    float worst = 0.0f;
    for (size_t p = 0; p < full.count(); ++p) {
      const float a = front.at(p, "A");
      covered += a == 1.0f;
      // The triangle's shadow on the quad, where the camera sees the quad: darker than the lit quad.
      shadowed += a == 0.0f && back.at(p, "A") == 1.0f && back.at(p, "B") < 0.02f;
      edges += a > 0.0f && a < 1.0f;
      for (const char* c : rgba) worst = std::max(worst, std::abs(plus(front, back, p, c) - full.at(p, c)));
    }
    const std::string what = sampling[1];
    EXPECT_LE(worst, 1e-5f) << what;
    EXPECT_GT(covered, 50u) << what;
    EXPECT_GT(shadowed, 20u) << what;
    if (sampling[1] == "1") {
      EXPECT_EQ(edges, 0u);
    }
    if (sampling[1] == "4") {
      EXPECT_GT(edges, 0u);
    }
    std::printf("spp %s: %zu of %zu pixels on layer edges; everywhere max |front plus back - full| %.3g\n",
                what.c_str(), edges, full.count(), worst);
  }
}

// --holdout: where the camera sees the triangle, alpha and colour are 0 and the quad behind it does
// not show; the rest of the image is the full render's, the triangle's shadow included. With
// --holdout-invisible the shadow is gone: the quad is lit exactly as in a scene without the
// triangle.
TEST(holdout_cli, a_holdout_cuts_alpha_and_keeps_or_drops_its_shadow) {
  const std::string dir = scratch_folder("holdout_matte");
  const std::string scene = write_scene(dir + "/scene.gltf");
  const image full = render(scene, dir, "full.exr", {});
  const image held = render(scene, dir, "held.exr", {"--holdout", "front_triangle"});
  const image invisible =
      render(scene, dir, "invisible.exr", {"--holdout", "front_*", "--holdout-invisible"});
  const image without = render(write_scene(dir + "/without.gltf", false), dir, "without.exr", {});
  size_t matte = 0, kept = 0, shadow_lifted = 0;
  for (size_t p = 0; p < full.count(); ++p) {
    const bool triangle = full.at(p, "R") > 2.0f * full.at(p, "B");  // red: the triangle
    if (triangle) {
      ++matte;
      for (const char* c : rgba) {
        EXPECT_EQ(held.at(p, c), 0.0f) << p;
        EXPECT_EQ(invisible.at(p, c), 0.0f) << p;
      }
      continue;
    }
    for (const char* c : rgba) {
      kept += held.at(p, c) == full.at(p, c);
      EXPECT_EQ(invisible.at(p, c), without.at(p, c)) << p << c;
    }
    shadow_lifted += invisible.at(p, "B") > full.at(p, "B") + 0.05f;
  }
  EXPECT_GT(matte, 100u);
  EXPECT_EQ(kept, 4 * (full.count() - matte));
  EXPECT_GT(shadow_lifted, 20u);  // the shadow the matte holdout keeps
}

TEST(holdout_cli, a_pattern_that_matches_no_node_is_refused_naming_the_nodes) {
  const std::string dir = scratch_folder("holdout_errors");
  const std::string scene = write_scene(dir + "/scene.gltf");
  const auto missing =
      run_kiln({"render", scene, "-o", dir + "/x.exr", "--holdout", "front_triangle,wheel*"});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.stderr_text.find("--holdout"), std::string::npos) << missing.stderr_text;
  EXPECT_NE(missing.stderr_text.find("wheel*"), std::string::npos) << missing.stderr_text;
  EXPECT_NE(missing.stderr_text.find("back_quad"), std::string::npos) << missing.stderr_text;
  const auto empty_item = run_kiln({"render", scene, "-o", dir + "/x.exr", "--only", "back_quad,"});
  EXPECT_EQ(empty_item.exit_code, 2);
  EXPECT_NE(empty_item.stderr_text.find("--only"), std::string::npos) << empty_item.stderr_text;
}

}  // namespace
}  // namespace kiln
