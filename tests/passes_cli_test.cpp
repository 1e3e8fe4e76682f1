// `--aovs albedo_filtered,N_filtered,diffuse,specular,shadow,emission` end to end, read back as a compositor
// or a denoiser would. A white-ish Lambert plane under one directional light, seen by an
// orthographic camera (so every lit sample has the same radiance), is half shadowed by a
// single-sided occluder the camera culls: the closed forms are the base colour for albedo_filtered,
// the plane's normal for N_filtered, 1 in the umbra and 0 in the light for the shadow matte, and
// diffuse + specular = direct. Filtered passes carry the beauty's own weights: at the shadow's edge
// the matte equals 1 − beauty / lit beauty, and at the plane's edge over the background the albedo
// and normal equal their value times alpha, for box, Blackman-Harris and adaptive sampling alike.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>

#include "render/film.h"
#include "support/channel_exr.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::gltf_builder;
using testing::run_kiln;
using testing::scratch_folder;

constexpr int size = 40;
const char* const rgb[3] = {".R", ".G", ".B"};
const char* const xyz[3] = {".X", ".Y", ".Z"};
constexpr float base = 0.8f;  // the plane's base colour (grey)

using image = testing::channel_exr;

size_t pixel(int x, int y) { return size_t(y) * size + size_t(x); }

// Renders scene to dir/name at 40x40, 32-bit float, with the given options, lit by the file's lights
// alone (the closed forms below are the punctual lights').
image render(const std::string& scene, const std::string& dir, const std::string& name,
             const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"--lighting", "file"};
  args.insert(args.end(), extra.begin(), extra.end());
  return image{testing::render_float_exr(scene, dir + "/" + name, size, size, args)};
}

// A quad in the plane z, spanning [x0, x1] × [y0, y1], facing +z (or -z when facing_back).
int add_quad(gltf_builder& b, float x0, float x1, float y0, float y1, float z, int material,
             bool facing_back) {
  const float nz = facing_back ? -1.0f : 1.0f;
  const std::vector<uint32_t> indices =
      facing_back ? std::vector<uint32_t>{0, 2, 1, 0, 3, 2} : std::vector<uint32_t>{0, 1, 2, 0, 2, 3};
  return b.add_node({{"mesh", b.add_mesh({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, indices,
                                         material, {{0, 0, nz}, {0, 0, nz}, {0, 0, nz}, {0, 0, nz}})}});
}

// The plane's material: grey, a rough dielectric (a Lambert and a GGX lobe), BLEND below opacity 1.
nlohmann::json grey_material(float opacity) {
  nlohmann::json grey = {{"pbrMetallicRoughness",
                          {{"baseColorFactor", {base, base, base, opacity}},
                           {"metallicFactor", 0.0},
                           {"roughnessFactor", 1.0}}}};
  if (opacity < 1.0f) grey["alphaMode"] = "BLEND";
  return grey;
}

// An orthographic camera on +z seeing [-1, 1]² and a directional light "sun" shining down -z.
void add_camera_and_sun(gltf_builder& b) {
  b.add_camera({{"type", "orthographic"},
                {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", 0.1}, {"zfar", 100.0}}}});
  b.add_node({{"camera", 0}, {"translation", {0, 0, 4}}});
  const int sun = b.add_light({{"type", "directional"}, {"name", "sun"}, {"intensity", 2.0}});
  b.add_node({{"extensions", {{"KHR_lights_punctual", {{"light", sun}}}}}});
}

// The plane z = 0 over [-plane_x, 1.5] × [-1.5, 1.5] (grey, rough dielectric: a Lambert and a GGX
// lobe), an orthographic camera on +z seeing [-1, 1]², a directional light "sun" shining down -z, and an
// occluder at z = 1 over x < 0 facing the plane: the camera culls its back face, the light's shadow
// rays do not, so the left half of the plane is in shadow with its edge at x = 0 (between columns
// 19 and 20). With plane_x < 1 the plane's left edge lies in view, over the background.
std::string shadowed_plane(const std::string& dir, float plane_x, float opacity = 1.0f) {
  gltf_builder b;
  const int grey = b.add_material(grey_material(opacity));
  add_quad(b, -plane_x, 1.5f, -1.5f, 1.5f, 0.0f, grey, false);
  add_quad(b, -3.0f, 0.0f, -3.0f, 3.0f, 1.0f, grey, true);
  add_camera_and_sun(b);
  // A second light shining up from below: it never reaches the plane's lit side, so it adds
  // nothing and its matte is 0 everywhere (not 1: nothing of it is blocked).
  const int under = b.add_light({{"type", "directional"}, {"name", "under"}, {"intensity", 5.0}});
  b.add_node({{"rotation", {1, 0, 0, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", under}}}}}});
  const std::string path = dir + "/plane_" + std::to_string(int(plane_x * 100)) + "_" +
                           std::to_string(int(opacity * 100)) + ".gltf";
  b.write(path);
  return path;
}

const std::vector<std::string> all_passes = {
    "--aovs", "beauty,direct,albedo_filtered,N_filtered,diffuse,specular,shadow"};

const std::vector<std::vector<std::string>> samplings = {
    {"--filter", "box", "--spp", "4"},
    {"--filter", "blackman-harris", "--spp", "4", "--sampler", "random"},
    {"--adaptive-threshold", "0.05", "--adaptive-depth", "3"},
};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// Away from the shadow's edge: albedo_filtered is the base colour and N_filtered the plane's normal
// (exactly: every sample files the same value and the weights divide out), the shadow matte is 1 in
// the umbra and 0 in the light, and there diffuse + specular = direct (1e-5 relative; no emission,
// no background in view), with both lobes lit.
TEST(passes_cli, closed_forms_on_a_half_shadowed_plane) {
  const std::string dir = scratch_folder("passes_closed_forms");
  const std::string scene = shadowed_plane(dir, 1.5f);
  for (const auto& sampling : samplings) {
    const image im = render(scene, dir, "plane.exr", with(all_passes, sampling));
    const std::string what = sampling[0] + " " + sampling[1];
    ASSERT_TRUE(im.has("shadow_sun.A") && im.has("shadow_under.A") && im.has("albedo_filtered.R") &&
                im.has("N_filtered.Z"))
        << what;
    float worst_sum = 0.0f;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const size_t p = pixel(x, y);
        // Box sums equal weights, exactly; Blackman-Harris's Σw·a / Σw and adaptive's Σ 2^-k·a round.
        const float tol = sampling[1] == "box" ? 0.0f : 1e-6f;
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(im.at(p, std::string("albedo_filtered") + rgb[c]), base, tol) << what << " " << x;
          EXPECT_NEAR(im.at(p, std::string("N_filtered") + xyz[c]), c == 2 ? 1.0f : 0.0f, tol) << what;
          const float direct = im.at(p, std::string("direct") + rgb[c]);
          const float lobes =
              im.at(p, std::string("diffuse") + rgb[c]) + im.at(p, std::string("specular") + rgb[c]);
          worst_sum = std::max(worst_sum, std::abs(lobes - direct) / std::max(1e-3f, std::abs(direct)));
        }
        EXPECT_EQ(im.at(p, "shadow_under.A"), 0.0f) << what;
        if (x >= 17 && x <= 22) continue;  // the shadow's edge, within the widest filter's reach
        const bool umbra = x < size / 2;
        EXPECT_NEAR(im.at(p, "shadow_sun.A"), umbra ? 1.0f : 0.0f, tol) << what << " " << x << "," << y;
        if (umbra) {
          EXPECT_EQ(im.at(p, "R"), 0.0f) << what;
          EXPECT_EQ(im.at(p, "diffuse.G"), 0.0f) << what;
        } else {
          EXPECT_GT(im.at(p, "diffuse.G"), 0.1f) << what;
          EXPECT_GT(im.at(p, "specular.G"), 1e-4f) << what;  // rough dielectric: F0 0.04 under GGX
          EXPECT_LT(im.at(p, "specular.G"), im.at(p, "diffuse.G")) << what;
        }
      }
    EXPECT_LE(worst_sum, 1e-5f) << what;
    std::printf("%s: max relative |diffuse + specular - direct| %.3g\n", what.c_str(), worst_sum);
  }
}

// The matte is filtered with the beauty's weights: every lit sample has the same radiance L (an
// orthographic view of a flat plane under a directional light), and a shadowed sample is black, so
// a pixel's beauty is L × (its samples' filtered share of light) and the matte must be 1 − R / L, on
// the edge pixels too, which Blackman-Harris and adaptive sampling make fractional. Box 0.5 keeps
// each sample in its pixel, so its edge is sharper than Blackman-Harris's.
TEST(passes_cli, shadow_matte_follows_the_beauty_weights_at_the_edge) {
  const std::string dir = scratch_folder("passes_edge");
  const std::string scene = shadowed_plane(dir, 1.5f);
  std::vector<float> edge_by_sampling;
  for (const auto& sampling : samplings) {
    const image im = render(scene, dir, "edge.exr", with(all_passes, sampling));
    const std::string what = sampling[0] + " " + sampling[1];
    const float lit = im.at(pixel(size - 3, size / 2), "R");
    ASSERT_GT(lit, 0.1f);
    float worst = 0.0f;
    int fractional = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const size_t p = pixel(x, y);
        const float matte = im.at(p, "shadow_sun.A");
        worst = std::max(worst, std::abs(matte - (1.0f - im.at(p, "R") / lit)));
        fractional += matte > 0.01f && matte < 0.99f;
      }
    EXPECT_LE(worst, 2e-6f) << what;
    if (sampling[0] != "--filter" || sampling[1] != "box") {
      EXPECT_GT(fractional, 0) << what;
    }
    edge_by_sampling.push_back(im.at(pixel(20, size / 2), "shadow_sun.A"));
    std::printf("%s: max |shadow - (1 - R/L)| %.3g, %d fractional pixels\n", what.c_str(), worst, fractional);
  }
  // Column 20 lies wholly in the light, but Blackman-Harris reaches into the shadow beside it.
  EXPECT_EQ(edge_by_sampling[0], 0.0f);
  EXPECT_GT(edge_by_sampling[1], 0.01f);
}

// Over the background a sample's albedo and normal count by its coverage, as its alpha does: at the
// plane's edge albedo_filtered = base × A and N_filtered.Z = A for each filter and adaptive sampling,
// while the unfiltered albedo keeps the nearest sample's value; a BLEND plane of opacity 0.5 over
// nothing covers half of each sample, so there too albedo_filtered = base × A (A = 0.5 inside).
TEST(passes_cli, albedo_and_normal_carry_the_coverage_at_an_object_edge) {
  const std::string dir = scratch_folder("passes_coverage");
  for (const float opacity : {1.0f, 0.5f})
    for (const auto& sampling : samplings) {
      const std::string scene = shadowed_plane(dir, 0.52f, opacity);  // the left edge inside column 9
      const image im = render(scene, dir, "cover.exr",
                              with({"--aovs", "beauty,albedo,albedo_filtered,N_filtered"}, sampling));
      const std::string what = sampling[0] + " " + sampling[1] + " opacity " + std::to_string(opacity);
      float worst = 0.0f;
      int partial = 0;
      for (size_t p = 0; p < im.count(); ++p) {
        const float alpha = im.at(p, "A");
        worst = std::max(worst, std::abs(im.at(p, "albedo_filtered.G") - base * alpha));
        worst = std::max(worst, std::abs(im.at(p, "N_filtered.Z") - alpha));
        if (alpha > 0.05f && alpha < 0.95f && opacity == 1.0f) {
          ++partial;
          EXPECT_TRUE(im.at(p, "albedo.G") == base || im.at(p, "albedo.G") == 0.0f) << what;
        }
      }
      EXPECT_TRUE(partial > 0 || opacity < 1.0f) << what;
      EXPECT_NEAR(im.at(pixel(size - 3, size / 2), "A"), opacity, 1e-6f) << what;
      EXPECT_LE(worst, 2e-6f) << what;
    }
}

// The documented albedo: a metal's base colour (its reflectance at normal incidence), 1 for glass
// whatever its tint (KHR_materials_transmission), and a perfect mirror's own colour, not what it
// reflects. N_filtered is the surfaces' own normal there too.
TEST(passes_cli, albedo_of_metal_and_glass) {
  const std::string dir = scratch_folder("passes_materials");
  gltf_builder b;
  const int metal = b.add_material(
      {{"pbrMetallicRoughness",
        {{"baseColorFactor", {0.9, 0.5, 0.25, 1}}, {"metallicFactor", 1.0}, {"roughnessFactor", 0.0}}}});
  const int glass = b.add_material(
      {{"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.75, 1.0, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.0}}},
       {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}});
  b.doc["extensionsUsed"] = {"KHR_materials_transmission"};
  add_quad(b, -1.5f, 0.0f, -1.5f, 1.5f, 0.0f, metal, false);
  add_quad(b, 0.0f, 1.5f, -1.5f, 1.5f, 0.0f, glass, false);
  b.add_camera({{"type", "orthographic"},
                {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", 0.1}, {"zfar", 100.0}}}});
  b.add_node({{"camera", 0}, {"translation", {0, 0, 4}}});
  const std::string scene = dir + "/materials.gltf";
  b.write(scene);
  const image im = render(scene, dir, "materials.exr",
                          {"--aovs", "beauty,albedo_filtered,N_filtered", "--background", "0.2,0.3,0.4"});
  const float metal_colour[3] = {0.9f, 0.5f, 0.25f};
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(im.at(pixel(5, size / 2), std::string("albedo_filtered") + rgb[c]), metal_colour[c]);
    EXPECT_EQ(im.at(pixel(size - 5, size / 2), std::string("albedo_filtered") + rgb[c]), 1.0f);
  }
  EXPECT_EQ(im.at(pixel(5, size / 2), "N_filtered.Z"), 1.0f);
  EXPECT_EQ(im.at(pixel(size - 5, size / 2), "N_filtered.Z"), 1.0f);
}

// An emissive quad beside a plain one, both grey and lit by "sun", seen straight on by the
// orthographic camera over [-1, 1]²: emission is the emissive factor × strength, (0.25, 0.5, 1) × 4,
// on the emissive half (columns 0-19) and 0 on the other, and emission + diffuse + specular = direct
// everywhere (nothing else is seen directly). At opacity 0.5 (BLEND over nothing) the quads cover
// half of each sample: emission is its value × A.
std::string emissive_and_plain_quads(const std::string& dir, float opacity) {
  gltf_builder b;
  const nlohmann::json grey = grey_material(opacity);
  nlohmann::json glowing = grey;
  glowing["emissiveFactor"] = {0.25, 0.5, 1.0};
  glowing["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}};
  b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  add_quad(b, -1.5f, 0.0f, -1.5f, 1.5f, 0.0f, b.add_material(glowing), false);
  add_quad(b, 0.0f, 1.5f, -1.5f, 1.5f, 0.0f, b.add_material(grey), false);
  add_camera_and_sun(b);
  const std::string path = dir + "/emissive_" + std::to_string(int(opacity * 100)) + ".gltf";
  b.write(path);
  return path;
}

TEST(passes_cli, emission_is_the_emitted_light_seen_directly) {
  const std::string dir = scratch_folder("passes_emission");
  const float emitted[3] = {1.0f, 2.0f, 4.0f};
  for (const float opacity : {1.0f, 0.5f})
    for (const auto& sampling : samplings) {
      const image im = render(emissive_and_plain_quads(dir, opacity), dir, "emission.exr",
                              with({"--aovs", "beauty,direct,diffuse,specular,emission"}, sampling));
      const std::string what = sampling[0] + " " + sampling[1] + " opacity " + std::to_string(opacity);
      ASSERT_TRUE(im.has("emission.R") && im.has("emission.G") && im.has("emission.B")) << what;
      float worst_sum = 0.0f;
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const size_t p = pixel(x, y);
          const float alpha = im.at(p, "A");
          for (int c = 0; c < 3; ++c) {
            const float emission = im.at(p, std::string("emission") + rgb[c]);
            const float direct = im.at(p, std::string("direct") + rgb[c]);
            const float rest =
                im.at(p, std::string("diffuse") + rgb[c]) + im.at(p, std::string("specular") + rgb[c]);
            worst_sum = std::max(worst_sum, std::abs(emission + rest - direct) / std::max(1e-3f, direct));
            if (x >= 17 && x <= 22) continue;  // the quads' seam, within the widest filter's reach
            const float expected = x < size / 2 ? emitted[c] * alpha : 0.0f;
            EXPECT_NEAR(emission, expected, 1e-6f * emitted[c]) << what << " " << x << "," << y;
          }
          if (x < 17) {
            EXPECT_GT(im.at(p, "diffuse.G"), 0.1f * alpha) << what;  // lit as well as glowing
          }
        }
      EXPECT_NEAR(im.at(pixel(5, size / 2), "A"), opacity, 1e-6f) << what;
      EXPECT_LE(worst_sum, 1e-5f) << what;
      std::printf("%s: max relative |emission + diffuse + specular - direct| %.3g\n", what.c_str(),
                  worst_sum);
    }
  // A compositor finds it by its Nuke layer name: one part named emission with --multipart.
  const auto multipart =
      run_kiln({"render", emissive_and_plain_quads(dir, 1.0f), "-o", dir + "/parts.exr", "--width", "8",
                "--height", "8", "-q", "--aovs", "beauty,emission", "--multipart"});
  ASSERT_EQ(multipart.exit_code, 0) << multipart.stderr_text;
  EXPECT_EQ(testing::exr_part_names_in(dir + "/parts.exr"), (std::set<std::string>{"rgba", "emission"}));
}

// Asking for the passes changes no beauty byte, they do not depend on threads or bands (a band is a
// crop of the frame, whose filter reach is traced and dropped), each light gets its
// own matte named after its light group, and --multipart writes each as a part of its own.
TEST(passes_cli, beauty_bytes_stay_and_passes_are_deterministic) {
  const std::string dir = scratch_folder("passes_bytes");
  const std::string scene = std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf";
  const std::vector<std::string> base_args = {"--filter", "tent", "--spp", "2", "--tile-size", "6"};
  const image plain =
      render(scene, dir, "plain.exr", with({"--aovs", "beauty,direct,lightgroups"}, base_args));
  const std::vector<std::string> passes = {
      "--aovs", "beauty,direct,lightgroups,albedo_filtered,N_filtered,diffuse,specular,shadow,emission"};
  const image one = render(scene, dir, "one.exr", with(with(passes, base_args), {"--threads", "1"}));
  const image two = render(scene, dir, "two.exr", with(with(passes, base_args), {"--threads", "2"}));
  const image band = render(scene, dir, "band.exr", with(with(passes, base_args), {"--band", "1/2"}));
  EXPECT_TRUE(one.has("shadow_ceiling_light.A") && one.has("shadow_fill_light.A"));
  size_t differing = 0, thread_differing = 0, band_differing = 0;
  float worst_sum = 0.0f;
  for (size_t p = 0; p < plain.count(); ++p) {
    for (const char* c : {"R", "G", "B", "A", "direct.R", "lightgroup_fill_light.G"})
      differing += plain.at(p, c) != one.at(p, c);
    for (const char* c : {"albedo_filtered.R", "N_filtered.Y", "diffuse.G", "specular.B",
                          "shadow_ceiling_light.A", "shadow_fill_light.A"}) {
      thread_differing += one.at(p, c) != two.at(p, c);
      const int y = int(p / size_t(size));
      if (y >= band.spec.y && y < band.spec.y + band.spec.height)
        band_differing += one.at(p, c) != band.at(p - size_t(band.spec.y) * size, c);
    }
    for (const char* s : {"ceiling_light", "fill_light"}) {
      const float matte = one.at(p, std::string("shadow_") + s + ".A");
      EXPECT_TRUE(matte >= 0.0f && matte <= 1.0f) << matte;
    }
    // The Cornell box is closed and has no emissive surfaces: the direct term is all lobes.
    for (int c = 0; c < 3; ++c) {
      const float direct = one.at(p, std::string("direct") + rgb[c]);
      const float lobes =
          one.at(p, std::string("diffuse") + rgb[c]) + one.at(p, std::string("specular") + rgb[c]);
      worst_sum = std::max(worst_sum, std::abs(lobes - direct) / std::max(1e-3f, std::abs(direct)));
    }
  }
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(thread_differing, 0u);
  EXPECT_EQ(band_differing, 0u);
  EXPECT_LE(worst_sum, 1e-5f);

  const auto multipart =
      run_kiln({"render", scene, "-o", dir + "/parts.exr", "--width", "16", "--height", "12", "-q", "--aovs",
                "beauty,albedo_filtered,N_filtered,diffuse,specular,shadow", "--multipart"});
  ASSERT_EQ(multipart.exit_code, 0) << multipart.stderr_text;
  const std::set<std::string> parts = testing::exr_part_names_in(dir + "/parts.exr");
  EXPECT_EQ(parts,
            (std::set<std::string>{"rgba", "albedo_filtered", "N_filtered", "diffuse", "specular",
                                   "shadow_ceiling_light", "shadow_fill_light", "shadow_environment"}));
}

// The memory estimate counts the passes' buffers: film_bytes equals the bytes the film allocates.
TEST(passes_cli, film_bytes_count_the_pass_buffers) {
  const aov_set a = aov_set_of({aov::beauty, aov::depth, aov::normal, aov::albedo_filtered,
                                aov::normal_filtered, aov::diffuse, aov::specular, aov::shadow});
  const std::vector<std::string> groups = {"lightgroup_a", "lightgroup_b", "lightgroup_c",
                                           "lightgroup_emission", "lightgroup_environment"};
  const film f(7, 5, a, groups);
  const uint64_t allocated =
      f.color.size() * sizeof(vec4) + f.depth.size() * sizeof(float) +
      f.vec3_layer(aov::normal).size() * sizeof(vec3) +
      (f.vec3_layer(aov::albedo_filtered).size() + f.vec3_layer(aov::normal_filtered).size() +
       f.vec3_layer(aov::diffuse).size() + f.vec3_layer(aov::specular).size()) *
          sizeof(vec3) +
      f.shadow.size() * sizeof(float);
  EXPECT_EQ(f.shadow.size(), size_t(7 * 5 * 4));  // three lights and the environment
  EXPECT_EQ(film_bytes(7, 5, a, int(groups.size())), allocated);
  EXPECT_EQ(f.shadow_layer(1), "shadow_b");
  EXPECT_EQ(f.shadow_layer(3), "shadow_environment");
}

}  // namespace
}  // namespace kiln
