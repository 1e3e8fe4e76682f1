// The working space end to end below the CLI: the shipped config's matrices against the published
// primaries (derived here independently of tools/ocio_matrices.py) and against OpenColorIO's own
// builtin ACES transforms; the EXR chromaticities each space gets; a scene's conversion (factors,
// lights, vertex colours, colour textures converted; data textures never; a shared image copied);
// and the one-line errors for a bad config or space.
#include "job/working_space.h"

#include <OpenColorIO/OpenColorIO.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "scene/colour_conversion.h"
#include "scene/texture_eval.h"

namespace kiln {
namespace {

namespace OCIO = OCIO_NAMESPACE;
namespace fs = std::filesystem;

const std::string config = KILN_SOURCE_DIR "/share/ocio/kiln.ocio";

working_space resolve(const std::string& space, const std::string& config_path = config) {
  render_options o;
  o.working_space = space;
  o.ocio_config = config_path;
  return resolve_working_space(o);
}

double largest_difference(const dmat3& a, const dmat3& b) {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) worst = std::max(worst, std::abs(a[c][r] - b[c][r]));
  return worst;
}

// The matrix of an OCIO builtin transform (in the given direction), sampled on the unit vectors.
dmat3 builtin_matrix(const char* style, OCIO::TransformDirection direction) {
  auto builtin = OCIO::BuiltinTransform::Create();
  builtin->setStyle(style);
  builtin->setDirection(direction);
  auto cpu = OCIO::Config::CreateRaw()->getProcessor(builtin)->getDefaultCPUProcessor();
  dmat3 m(0.0);
  for (int c = 0; c < 3; ++c) {
    float v[3] = {0, 0, 0};
    v[c] = 1.0f;
    cpu->applyRGB(v);
    m[c] = dvec3(v[0], v[1], v[2]);
  }
  return m;
}

TEST(working_space, the_shipped_config_matches_the_published_primaries_and_ocio_builtins) {
  const working_space acescg = resolve("ACEScg");
  EXPECT_EQ(acescg.name, "ACEScg");
  const dmat3 published_ap1 = rgb_to_rgb(rec709_primaries(), ap1_primaries());
  // OCIO processes in float32: the sampled matrix holds the config's entries to about 1e-7.
  EXPECT_LT(largest_difference(acescg.from_rec709, published_ap1), 1e-6);
  EXPECT_NEAR(acescg.from_rec709[0][0], 0.6131, 1e-4);  // the ACES documents' Rec.709 -> AP1, rounded
  EXPECT_NEAR(acescg.from_rec709[1][0], 0.3395, 1e-4);
  const dmat3 builtin_ap1 =
      builtin_matrix("UTILITY - ACES-AP1_to_LINEAR-REC709_BFD", OCIO::TRANSFORM_DIR_INVERSE);
  EXPECT_LT(largest_difference(acescg.from_rec709, builtin_ap1), 1e-6);

  const working_space aces = resolve("ACES2065-1");
  EXPECT_LT(largest_difference(aces.from_rec709, rgb_to_rgb(rec709_primaries(), ap0_primaries())), 1e-6);
  const dmat3 builtin_ap0 = builtin_matrix("ACEScg_to_ACES2065-1", OCIO::TRANSFORM_DIR_FORWARD) * builtin_ap1;
  EXPECT_LT(largest_difference(aces.from_rec709, builtin_ap0), 1e-6);

  // An alias resolves to the config's name; Rec.709 itself is the identity.
  EXPECT_EQ(resolve("lin_ap1").name, "ACEScg");
  EXPECT_EQ(resolve("lin_rec709").from_rec709, dmat3(1.0));
}

TEST(working_space, chromaticities_name_the_working_space) {
  EXPECT_EQ(resolve("ACEScg").primaries.xy, ap1_primaries().xy);
  EXPECT_EQ(resolve("ACES2065-1").primaries.xy, ap0_primaries().xy);
  EXPECT_EQ(resolve("Linear Rec.709 (sRGB)").primaries.xy, rec709_primaries().xy);
  EXPECT_EQ(working_space{}.primaries.xy, rec709_primaries().xy);
  EXPECT_FALSE(working_space{}.converts());
}

TEST(working_space, no_working_space_converts_nothing_and_reads_only_a_named_config) {
  ::setenv("OCIO", "/nonexistent/env.ocio", 1);  // a session's $OCIO is read only when used
  render_options o;
  EXPECT_FALSE(resolve_working_space(o).converts());
  ::unsetenv("OCIO");
  o.ocio_config = config;
  EXPECT_FALSE(resolve_working_space(o).converts());
  o.ocio_config = "/nonexistent.ocio";  // one named on the command line is checked
  EXPECT_THROW(resolve_working_space(o), error);
}

// A scene of one material reading a colour texture and a data texture from the same image.
scene textured_scene() {
  scene s;
  s.images.push_back(image{"two texels", 2, 1, {255, 0, 0, 255, 10, 128, 200, 128}, {}});
  s.textures.push_back({0, {}});
  material m;
  m.base_color_factor = vec4(0.5f, 0.25f, 1.0f, 0.75f);
  m.base_color_texture.texture = 0;
  m.metallic_roughness_texture.texture = 0;
  m.emissive_factor = vec3(1.0f, 0.0f, 0.0f);
  s.materials.push_back(m);
  light l;
  l.color = vec3(0.0f, 1.0f, 0.0f);
  s.lights.push_back(l);
  mesh me;
  me.colors0 = {vec4(0.0f, 0.0f, 1.0f, 0.5f)};
  s.meshes.push_back(me);
  s.env.color = vec3(1.0f);
  return s;
}

TEST(working_space, a_scene_converts_colours_and_never_data) {
  const working_space acescg = resolve("ACEScg");
  const mat3 m(acescg.from_rec709);
  scene s = textured_scene();
  const scene before = s;
  apply_working_space(s, acescg, nullptr);
  const material& mat = s.materials[0];
  EXPECT_EQ(vec3(mat.base_color_factor), m * vec3(before.materials[0].base_color_factor));
  EXPECT_EQ(mat.base_color_factor.a, 0.75f);
  EXPECT_EQ(mat.emissive_factor, m * vec3(1, 0, 0));
  EXPECT_EQ(s.lights[0].color, m * vec3(0, 1, 0));
  EXPECT_EQ(vec3(s.meshes[0].colors0[0]), m * vec3(0, 0, 1));
  EXPECT_EQ(s.meshes[0].colors0[0].a, 0.5f);
  // White stays white: the matrices keep the white point (Bradford-adapted), to float rounding.
  EXPECT_NEAR(s.env.color.r, 1.0f, 1e-6f);
  EXPECT_NEAR(s.env.color.b, 1.0f, 1e-6f);

  // The shared image was copied: the data slot reads the file's bytes, the colour slot the copy.
  ASSERT_EQ(s.images.size(), 2u);
  EXPECT_EQ(s.images[0].texels8, before.images[0].texels8);
  EXPECT_EQ(s.textures[size_t(mat.metallic_roughness_texture.texture)].image, 0u);
  const uint32_t colour = s.textures[size_t(mat.base_color_texture.texture)].image;
  ASSERT_EQ(colour, 1u);
  for (int x = 0; x < 2; ++x) {
    const vec4 original = fetch_texel(before.images[0], x, 0, texel_encoding::srgb);
    const vec4 converted = fetch_texel(s.images[colour], x, 0, texel_encoding::srgb);
    const vec3 expected = m * vec3(original);
    for (int c = 0; c < 3; ++c)  // the sRGB round trip costs a few float ulps
      EXPECT_NEAR(converted[c], expected[c], 1e-6f * std::max(1.0f, std::abs(expected[c]))) << x << c;
    EXPECT_EQ(converted.a, original.a);
  }
}

TEST(working_space, float_colour_textures_and_the_environment_map_convert_in_place) {
  const working_space acescg = resolve("ACEScg");
  const mat3 m(acescg.from_rec709);
  scene s;
  // A 16-bit or float colour texture (sRGB-encoded floats, one above 1) and an environment map
  // (linear radiance), neither shared with a data slot.
  s.images.push_back(image{"colour", 1, 1, {}, {0.2f, 0.9f, 1.5f, 0.5f}});
  s.images.push_back(image{"sky", 1, 1, {}, {3.0f, 0.25f, 0.0f, 1.0f}});
  s.textures.push_back({0, {}});
  material mat;
  mat.emissive_texture.texture = 0;
  s.materials.push_back(mat);
  s.env.map_image = 1;
  const scene before = s;
  apply_working_space(s, acescg, nullptr);
  ASSERT_EQ(s.images.size(), 2u);  // nothing copied
  const vec3 colour = m * vec3(fetch_texel(before.images[0], 0, 0, texel_encoding::srgb));
  const vec4 converted = fetch_texel(s.images[0], 0, 0, texel_encoding::srgb);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(converted[c], colour[c], 1e-6f * std::max(1.0f, colour[c])) << c;
  EXPECT_EQ(converted.a, 0.5f);
  const vec4 sky = fetch_texel(s.images[1], 0, 0, texel_encoding::linear);
  EXPECT_EQ(vec3(sky), m * vec3(3.0f, 0.25f, 0.0f));  // linear: no round trip at all
  EXPECT_EQ(sky.a, 1.0f);
}

TEST(working_space, the_srgb_encoding_inverts_the_decoding_everywhere) {
  for (float v : {-0.5f, -1e-4f, 0.0f, 1e-4f, 0.0031308f, 0.01f, 0.18f, 0.5f, 1.0f, 4.0f, 100.0f})
    EXPECT_NEAR(srgb_to_linear(linear_to_srgb(v)), v, 2e-6f * std::max(1.0f, std::abs(v))) << v;
}

// The message of what resolving throws, or "" when nothing is thrown.
std::string failure(const std::string& space, const std::string& config_path) {
  try {
    resolve(space, config_path);
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::input) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.what();
  }
  return "";
}

TEST(working_space, a_bad_config_or_space_is_one_line_naming_file_and_option) {
  // A near miss is named, and the spaces a render can work in are listed (not the data space Raw).
  EXPECT_EQ(
      failure("ACEScgg", config),
      config +
          ": --working-space: the config has no colour space 'ACEScgg'; did you mean 'ACEScg'? (its colour "
          "spaces: 'ACES2065-1', 'ACEScg', 'Linear Rec.709 (sRGB)', 'sRGB - Display')");
  EXPECT_EQ(failure("AP1", config),
            config +
                ": --working-space: the config has no colour space 'AP1' (its colour spaces: 'ACES2065-1', "
                "'ACEScg', 'Linear Rec.709 (sRGB)', 'sRGB - Display')");
  EXPECT_NE(failure("Raw", config).find("is a data space"), std::string::npos);
  EXPECT_NE(failure("sRGB - Display", config).find("not a linear (3x3 matrix) transform"), std::string::npos);
  EXPECT_EQ(failure("ACEScg", "/nonexistent/x.ocio"),
            "/nonexistent/x.ocio: --ocio-config: no such OpenColorIO config file");
  const fs::path broken = fs::temp_directory_path() / "kiln_broken_config.ocio";
  std::ofstream(broken) << "ocio_profile_version: 2\ncolorspaces: [ {\n";
  const std::string message = failure("ACEScg", broken.string());
  EXPECT_EQ(message.rfind(broken.string() + ": --ocio-config: not a valid OpenColorIO config: ", 0), 0u)
      << message;
  fs::remove(broken);
  // $OCIO is named as such when it names the config.
  ::setenv("OCIO", "/nonexistent/env.ocio", 1);
  render_options o;
  o.working_space = "ACEScg";
  try {
    resolve_working_space(o);
    ADD_FAILURE() << "no error";
  } catch (const error& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/env.ocio: $OCIO: no such OpenColorIO config file");
  }
  ::unsetenv("OCIO");
}

TEST(working_space, the_preview_goes_through_ocio_only_when_asked) {
  ::unsetenv("OCIO");
  render_options o;
  EXPECT_FALSE(preview_view(o));
  o.ocio_config = config;
  const std::optional<display_transform> view = preview_view(o);
  ASSERT_TRUE(view);
  // kiln's sRGB display, Standard view, from linear Rec.709: the exact piecewise sRGB curve.
  float rgb[6] = {0.0031308f, 0.18f, 0.5f, 1.0f, 0.0f, 2.0f};
  (*view)(rgb, 2);
  EXPECT_NEAR(rgb[0], 0.04045f, 1e-6f);
  EXPECT_NEAR(rgb[1], 1.055f * std::pow(0.18f, 1 / 2.4f) - 0.055f, 1e-6f);
  EXPECT_NEAR(rgb[2], 1.055f * std::pow(0.5f, 1 / 2.4f) - 0.055f, 1e-6f);
  EXPECT_NEAR(rgb[3], 1.0f, 1e-6f);
  // A display or view the config lacks: the one line names the near miss and what there is.
  auto refusal = [&o]() -> std::string {
    try {
      preview_view(o);
    } catch (const error& e) {
      return e.what();
    }
    return "no error";
  };
  o.display = "P3";
  EXPECT_EQ(refusal(), config + ": --display: the config has no display 'P3' (its displays: 'sRGB')");
  o.display = "sRGB";
  o.view = "Standrd";
  EXPECT_EQ(refusal(),
            config +
                ": --view: the display 'sRGB' has no view 'Standrd'; did you mean 'Standard'? (its "
                "views: 'Standard', 'Raw')");
}

}  // namespace
}  // namespace kiln
