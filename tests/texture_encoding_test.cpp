// Colour-space decoding of textures through the CLI, on content like the TextureEncodingTest
// sample: quads textured with one 8-bit texel value each are compared with quads that carry the
// equivalent factors. Base colour and emissive textures are sRGB (the decoded value, not v/255);
// the metallic-roughness texture is linear (G = roughness, B = metallic, as stored).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using nlohmann::json;

// The sRGB transfer function's inverse (IEC 61966-2-1), written here rather than taken from
// the renderer.
double srgb_decode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// The texels: base colour / emissive (R, G, B) and metallic-roughness (G = roughness, B = metallic;
// R is occlusion and unused here). Distinct values per channel catch swapped channels.
constexpr std::array<int, 3> colour_texel = {64, 128, 192};
constexpr int roughness_texel = 200, metallic_texel = 128;

// A 4×4 RGBA PNG of one texel value.
void write_png(const std::string& path, const std::array<int, 3>& rgb) {
  std::vector<uint8_t> pixels;
  for (int i = 0; i < 16; ++i)
    pixels.insert(pixels.end(), {uint8_t(rgb[0]), uint8_t(rgb[1]), uint8_t(rgb[2]), uint8_t(255)});
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << OIIO::geterror();
  OIIO::ImageSpec spec(4, 4, 4, OIIO::TypeDesc::UINT8);
  ASSERT_TRUE(out->open(path, spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data())) << out->geterror();
  out->close();
}

json unlit(json material) {
  material["extensions"]["KHR_materials_unlit"] = json::object();
  return material;
}

// A lit dielectric-metal mix under the directional light; only the metallic-roughness inputs vary.
json lit(json pbr) {
  pbr["baseColorFactor"] = {0.8, 0.6, 0.4, 1.0};
  return {{"pbrMetallicRoughness", pbr}};
}

// The quads, left to right, one per material, each 1.6 wide at x = -7, -5, ..., facing +z.
enum quad : int {
  base_texture,       // unlit, baseColorTexture = colour_texel
  base_factor,        // unlit, baseColorFactor = sRGB-decoded colour_texel
  emissive_texture,   // black, no specular, emissiveTexture = colour_texel
  emissive_factor,    // black, no specular, emissiveFactor = sRGB-decoded colour_texel
  mr_texture,         // lit, metallicRoughnessTexture
  mr_factor,          // lit, metallic = 128/255, roughness = 200/255
  mr_factor_srgb,     // lit, the factors a wrong sRGB decode of the texture would give
  mr_factor_swapped,  // lit, the factors a swap of the G and B channels would give
  quad_count
};

constexpr double quad_spacing = 2.0, quad_half = 0.8;
double quad_x(int q) { return (q - (quad_count - 1) / 2.0) * quad_spacing; }

std::string write_scene(const std::string& dir) {
  write_png(dir + "/colour.png", colour_texel);
  write_png(dir + "/metal_rough.png", {200, roughness_texel, metallic_texel});

  testing::gltf_builder b;
  json& doc = b.doc;
  doc["images"] = {{{"uri", "colour.png"}}, {{"uri", "metal_rough.png"}}};
  doc["samplers"] = {{{"magFilter", 9728}, {"minFilter", 9728}}};  // NEAREST
  doc["textures"] = {{{"source", 0}, {"sampler", 0}}, {{"source", 1}, {"sampler", 0}}};
  doc["extensionsUsed"] = {"KHR_materials_unlit", "KHR_materials_specular"};

  json decoded = json::array();
  for (int c : colour_texel) decoded.push_back(srgb_decode(c / 255.0));
  const double metallic = metallic_texel / 255.0, roughness = roughness_texel / 255.0;
  const json black_emitter = {
      {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0}}},
      {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0}}}}}};
  std::vector<json> materials(quad_count);
  materials[base_texture] = unlit({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  materials[base_factor] =
      unlit({{"pbrMetallicRoughness", {{"baseColorFactor", {decoded[0], decoded[1], decoded[2], 1.0}}}}});
  materials[emissive_texture] = black_emitter;
  materials[emissive_texture]["emissiveTexture"] = {{"index", 0}};
  materials[emissive_texture]["emissiveFactor"] = {1, 1, 1};
  materials[emissive_factor] = black_emitter;
  materials[emissive_factor]["emissiveFactor"] = decoded;
  materials[mr_texture] = lit({{"metallicRoughnessTexture", {{"index", 1}}}});
  materials[mr_factor] = lit({{"metallicFactor", metallic}, {"roughnessFactor", roughness}});
  materials[mr_factor_srgb] =
      lit({{"metallicFactor", srgb_decode(metallic)}, {"roughnessFactor", srgb_decode(roughness)}});
  materials[mr_factor_swapped] = lit({{"metallicFactor", roughness}, {"roughnessFactor", metallic}});

  for (int q = 0; q < quad_count; ++q) {
    const float x0 = float(quad_x(q) - quad_half), x1 = float(quad_x(q) + quad_half);
    const float y = float(quad_half);
    const int mesh = b.add_mesh({{x0, -y, 0}, {x1, -y, 0}, {x1, y, 0}, {x0, y, 0}}, {0, 1, 2, 0, 2, 3},
                                b.add_material(materials[size_t(q)]), {}, {{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    b.add_node({{"mesh", mesh}});
  }
  // Orthographic view straight down -z and a directional light: every lit quad sees the same
  // view and light directions, so equal materials give equal pixels.
  const double xmag = quad_count * quad_spacing / 2.0;
  const int camera =
      b.add_camera({{"type", "orthographic"},
                    {"orthographic", {{"xmag", xmag}, {"ymag", 1.0}, {"znear", 0.1}, {"zfar", 100}}}});
  b.add_node({{"camera", camera}, {"translation", {0, 0, 10}}});
  const int light = b.add_light({{"type", "directional"}, {"intensity", 3.0}});
  // Light travels along the node's -z; tilt it so the highlight is off the mirror direction.
  b.add_node({{"extensions", {{"KHR_lights_punctual", {{"light", light}}}}},
              {"rotation", {0.2588190451, 0.0, 0.0, 0.9659258263}}});  // 30° about x
  const std::string path = dir + "/encoding.gltf";
  b.write(path);
  return path;
}

struct rgb {
  double c[3];
};

// Renders the scene with 32-bit float colour and returns the pixel at each quad's centre.
std::vector<rgb> render_quad_centres() {
  const std::string dir = testing::scratch_folder("texture_encoding");
  const std::string scene = write_scene(dir), out = dir + "/out.exr";
  const int width = 40 * quad_count, height = 40;  // the camera's aspect xmag / ymag
  auto result = testing::run_kiln({"render", scene, "-o", out, "--width", std::to_string(width), "--height",
                                   std::to_string(height), "--float", "--threads", "2", "-q", "--lighting",
                                   "headlight"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  std::vector<rgb> centres;
  auto in = OIIO::ImageInput::open(out);
  if (!in) {
    ADD_FAILURE() << "cannot read " << out;
    return centres;
  }
  EXPECT_EQ(in->spec().width, width);
  EXPECT_EQ(in->spec().channelformat(0), OIIO::TypeDesc::FLOAT);
  std::vector<float> pixels(size_t(width) * height * 3);
  EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, pixels.data()));
  for (int q = 0; q < quad_count; ++q) {
    const int x = 40 * q + 20, y = height / 2;  // 40 pixels per quad spacing, centred
    const float* p = &pixels[(size_t(y) * width + x) * 3];
    centres.push_back({{p[0], p[1], p[2]}});
  }
  return centres;
}

double relative_difference(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-6); }

TEST(texture_encoding, srgb_textures_decode_and_the_metallic_roughness_texture_stays_linear) {
  const std::vector<rgb> seen = render_quad_centres();
  ASSERT_EQ(seen.size(), size_t(quad_count));
  for (int c = 0; c < 3; ++c) {
    const double v = colour_texel[size_t(c)] / 255.0, expected = srgb_decode(v);
    // Base colour: the textured quad equals the decoded factor and the analytic decode, and is
    // far from the undecoded v/255.
    EXPECT_LT(relative_difference(seen[base_texture].c[c], seen[base_factor].c[c]), 1e-3) << "channel " << c;
    EXPECT_LT(relative_difference(seen[base_texture].c[c], expected), 1e-3) << "channel " << c;
    EXPECT_GT(relative_difference(seen[base_texture].c[c], v), 0.2) << "channel " << c;
    // Emissive likewise.
    EXPECT_LT(relative_difference(seen[emissive_texture].c[c], seen[emissive_factor].c[c]), 1e-3)
        << "channel " << c;
    EXPECT_LT(relative_difference(seen[emissive_texture].c[c], expected), 1e-3) << "channel " << c;
    EXPECT_GT(relative_difference(seen[emissive_texture].c[c], v), 0.2) << "channel " << c;
    // Metallic-roughness: the texture reads as the linear factors, not the decoded or swapped ones.
    EXPECT_LT(relative_difference(seen[mr_texture].c[c], seen[mr_factor].c[c]), 1e-3) << "channel " << c;
    EXPECT_GT(relative_difference(seen[mr_texture].c[c], seen[mr_factor_srgb].c[c]), 0.05) << "channel " << c;
    EXPECT_GT(relative_difference(seen[mr_texture].c[c], seen[mr_factor_swapped].c[c]), 0.05)
        << "channel " << c;
    EXPECT_GT(seen[mr_texture].c[c], 0.01) << "the lit quads are lit, channel " << c;
  }
  const char* names[] = {
      "base texture", "base factor",       "emissive texture",        "emissive factor",
      "mr texture",   "mr linear factors", "mr sRGB-decoded factors", "mr swapped factors"};
  for (int q = 0; q < quad_count; ++q)
    std::printf("%-24s %.6f %.6f %.6f\n", names[q], seen[size_t(q)].c[0], seen[size_t(q)].c[1],
                seen[size_t(q)].c[2]);
}

}  // namespace
}  // namespace kiln
