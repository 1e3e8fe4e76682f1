// The compositing outputs of `kiln render` end to end. Cryptomatte, decoded the way a compositor
// does: the manifest names exactly the scene's objects and materials with their MurmurHash3 ids,
// the coverages of a pixel sum to its alpha, an object's matte equals the alpha of a render of that
// object alone, and the channels are the same bytes for any thread count and for --tile bands.
// --depth-mode planar against an analytic plane. The light split (direct, reflection, refraction)
// sums to the beauty, leaves the beauty's bytes alone and is zero where no ray was spawned.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "io/exr/murmur3.h"
#include "support/float_exr.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::gltf_builder;
using testing::run_kiln;
using testing::scratch_folder;

constexpr int size = 48;

// The objects of the test scene, seen by a camera at z = 4 looking down -Z: a triangle in front
// (z = 0.5), a quad partly behind it (z = 0) and an unnamed triangle without a material further
// back (z = -0.5). Their slanted edges give every filter fractional coverage.
enum scene_part { front = 1, back = 2, unnamed = 4 };

std::string write_scene(const std::string& path, int parts) {
  gltf_builder b;
  const int red =
      b.add_material({{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}});
  const int blue =
      b.add_material({{"name", "blue"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 1, 1}}}}});
  if (parts & front)
    b.add_node({{"name", "front_triangle"},
                {"mesh", b.add_mesh({{-0.9f, -0.7f, 0.5f}, {0.6f, -0.5f, 0.5f}, {-0.2f, 0.8f, 0.5f}},
                                    {0, 1, 2}, red)}});
  if (parts & back)
    b.add_node({{"name", "back_quad"},
                {"mesh", b.add_mesh({{-0.3f, -0.9f, 0}, {1.0f, -0.6f, 0}, {0.9f, 0.9f, 0}, {-0.1f, 0.6f, 0}},
                                    {0, 1, 2, 0, 2, 3}, blue)}});
  if (parts & unnamed)
    b.add_node({{"mesh",
                 b.add_mesh({{-1.2f, 0.3f, -0.5f}, {-0.5f, 0.4f, -0.5f}, {-0.9f, 1.1f, -0.5f}}, {0, 1, 2})}});
  const int camera =
      b.add_camera({{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}});
  b.add_node({{"camera", camera}, {"translation", {0, 0, 4}}});
  b.write(path);
  return path;
}

// The file's channels as float, looked up by name.
struct image : testing::float_exr {
  float at(size_t pixel, const std::string& channel) const {
    const int c = spec.channelindex(channel);
    EXPECT_GE(c, 0) << channel;
    return c < 0 ? NAN : pixels[pixel * size_t(spec.nchannels) + size_t(c)];
  }
  size_t count() const { return spec.image_pixels(); }
};

image read(const std::string& path) { return image{testing::read_float_exr(path)}; }

// Renders scene to dir/name at 48x48 with 32-bit float colour and the given options.
image render(const std::string& scene, const std::string& dir, const std::string& name,
             std::vector<std::string> extra) {
  std::vector<std::string> args = {"render",   scene,
                                   "-o",       dir + "/" + name,
                                   "--width",  std::to_string(size),
                                   "--height", std::to_string(size),
                                   "-q",       "--float"};
  args.insert(args.end(), extra.begin(), extra.end());
  auto result = run_kiln(args);
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  return read(dir + "/" + name);
}

// The specification's uint32_to_float32, written out again here: the exponent clamped to [1, 254].
uint32_t id_bits(const std::string& name) {
  const uint32_t h = murmur3_x86_32(name, 0);
  uint32_t exponent = (h >> 23) & 0xffu;
  exponent = std::min(std::max(exponent, 1u), 254u);
  return (h & 0x807fffffu) | (exponent << 23);
}

float id_float(uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

std::string hex8(uint32_t bits) {
  char text[9];
  std::snprintf(text, sizeof text, "%08x", bits);
  return text;
}

// The header attributes of the layer called layer_name: {"name", "hash", "conversion", "manifest"}.
std::map<std::string, std::string> layer_metadata(const OIIO::ImageSpec& spec,
                                                  const std::string& layer_name) {
  std::map<std::string, std::string> out;
  for (const OIIO::ParamValue& p : spec.extra_attribs) {
    const std::string name = p.name().string();
    if (name.rfind("cryptomatte/", 0) != 0 ||
        spec.get_string_attribute(name.substr(0, 20) + "name") != layer_name)
      continue;
    out[name.substr(20)] = spec.get_string_attribute(name);
    out["key"] = name.substr(12, 7);
  }
  return out;
}

// A compositor's decode: the matte of id is the summed coverage of the ranks holding it.
float matte(const image& im, size_t pixel, const std::string& layer, float id, int depth = 6) {
  float sum = 0.0f;
  for (int rank = 0; rank < depth; ++rank) {
    char set[8];
    std::snprintf(set, sizeof set, "%02d", rank / 2);
    const std::string prefix = layer + set + (rank % 2 == 0 ? ".R" : ".B");
    const std::string coverage = layer + set + (rank % 2 == 0 ? ".G" : ".A");
    if (im.at(pixel, prefix) == id) sum += im.at(pixel, coverage);
  }
  return sum;
}

float coverage_sum(const image& im, size_t pixel, const std::string& layer, int depth = 6) {
  float sum = 0.0f;
  for (int rank = 0; rank < depth; ++rank) {
    char set[8];
    std::snprintf(set, sizeof set, "%02d", rank / 2);
    sum += im.at(pixel, layer + set + (rank % 2 == 0 ? ".G" : ".A"));
  }
  return sum;
}

class cryptomatte_cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = scratch_folder("cryptomatte");
    full_ = write_scene(dir_ + "/full.gltf", front | back | unnamed);
    front_only_ = write_scene(dir_ + "/front.gltf", front);
    front_back_ = write_scene(dir_ + "/front_back.gltf", front | back);
  }
  std::string dir_, full_, front_only_, front_back_;
};

TEST_F(cryptomatte_cli, manifest_names_exactly_the_scene_objects_and_materials) {
  const image im = render(full_, dir_, "m.exr", {"--aovs", "beauty,cryptomatte"});
  const auto objects = layer_metadata(im.spec, "CryptoObject");
  const auto materials = layer_metadata(im.spec, "CryptoMaterial");
  for (const auto* layer : {&objects, &materials}) {
    EXPECT_EQ(layer->at("hash"), "MurmurHash3_32");
    EXPECT_EQ(layer->at("conversion"), "uint32_to_float32");
  }
  EXPECT_EQ(objects.at("key"), hex8(murmur3_x86_32("CryptoObject")).substr(0, 7));
  EXPECT_EQ(materials.at("key"), hex8(murmur3_x86_32("CryptoMaterial")).substr(0, 7));
  const nlohmann::json object_manifest = nlohmann::json::parse(objects.at("manifest"));
  const nlohmann::json material_manifest = nlohmann::json::parse(materials.at("manifest"));
  nlohmann::json expected_objects, expected_materials;
  for (const char* name : {"front_triangle", "back_quad", "node2"})
    expected_objects[name] = hex8(id_bits(name));
  for (const char* name : {"red", "blue", "default"}) expected_materials[name] = hex8(id_bits(name));
  EXPECT_EQ(object_manifest, expected_objects);
  EXPECT_EQ(material_manifest, expected_materials);
  // Only what was asked for.
  const image objects_only = render(full_, dir_, "o.exr", {"--aovs", "crypto_object"});
  EXPECT_EQ(objects_only.spec.nchannels, 12);
  EXPECT_TRUE(layer_metadata(objects_only.spec, "CryptoMaterial").empty());
  // OpenImageIO lists per-channel formats only when they differ: here every channel is float.
  EXPECT_EQ(objects_only.spec.format, OIIO::TypeDesc::FLOAT);
  for (int c = 0; c < objects_only.spec.nchannels; ++c)
    EXPECT_EQ(objects_only.spec.channelformat(c), OIIO::TypeDesc::FLOAT);
}

// Coverage of every pixel sums to alpha (the background is transparent), and the front triangle's
// matte is the alpha of a render of the front triangle alone: the same samples with the same
// weights, resolved by the colour path instead of the id path. The back quad's matte is the alpha
// the back quad adds to the front triangle. Both paths are float; their rounding differs by well
// under the 1e-5 asserted.
TEST_F(cryptomatte_cli, coverage_matches_alpha_for_every_filter_and_sampler) {
  const std::vector<std::vector<std::string>> samplings = {
      {"--filter", "box", "--spp", "16"},
      {"--filter", "tent", "--spp", "9"},
      {"--filter", "gaussian", "--spp", "4", "--sampler", "random"},
      {"--filter", "blackman-harris", "--spp", "5", "--tile-size", "7"},
      {"--adaptive-threshold", "0.05", "--adaptive-depth", "3"},
  };
  const float tolerance = 1e-5f;
  const float front_id = id_float(id_bits("front_triangle")), back_id = id_float(id_bits("back_quad"));
  const float red = id_float(id_bits("red"));
  for (const auto& sampling : samplings) {
    std::vector<std::string> args = {"--aovs", "beauty,cryptomatte"};
    args.insert(args.end(), sampling.begin(), sampling.end());
    const image full = render(full_, dir_, "full.exr", args);
    const image alone = render(front_only_, dir_, "front.exr", args);
    const image two = render(front_back_, dir_, "two.exr", args);
    float sum_error = 0.0f, front_error = 0.0f, back_error = 0.0f, material_error = 0.0f;
    size_t fractional = 0;
    for (size_t p = 0; p < full.count(); ++p) {
      const float alpha = full.at(p, "A");
      sum_error = std::max({sum_error, std::abs(coverage_sum(full, p, "CryptoObject") - alpha),
                            std::abs(coverage_sum(full, p, "CryptoMaterial") - alpha)});
      const float front_matte = matte(full, p, "CryptoObject", front_id);
      front_error = std::max(front_error, std::abs(front_matte - alone.at(p, "A")));
      back_error = std::max(back_error, std::abs(matte(full, p, "CryptoObject", back_id) -
                                                 (two.at(p, "A") - alone.at(p, "A"))));
      material_error =
          std::max(material_error, std::abs(matte(full, p, "CryptoMaterial", red) - front_matte));
      fractional += front_matte > 0.01f && front_matte < 0.99f;
    }
    const std::string what = sampling[0] + " " + sampling[1];
    EXPECT_LE(sum_error, tolerance) << what;
    EXPECT_LE(front_error, tolerance) << what;
    EXPECT_LE(back_error, tolerance) << what;
    EXPECT_EQ(material_error, 0.0f) << what;  // one object, one material: the same sums
    EXPECT_GE(fractional, 20u) << what;       // the edges are anti-aliased, not a binary mask
    std::printf(
        "%s: max |coverage sum - alpha| %.3g, max |front matte - front alone alpha| %.3g, "
        "max |back matte - alpha difference| %.3g, %zu fractional front pixels\n",
        what.c_str(), sum_error, front_error, back_error, fractional);
  }
}

// The raw bytes of the Cryptomatte channels (rows y0..y1 of the image's data window).
std::vector<float> crypto_channels(const image& im, int y0, int y1) {
  std::vector<float> out;
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < im.spec.width; ++x)
      for (int c = 0; c < im.spec.nchannels; ++c)
        if (im.spec.channelnames[size_t(c)].rfind("Crypto", 0) == 0)
          out.push_back(im.pixels[(size_t(y - im.spec.y) * im.spec.width + x) * im.spec.nchannels + c]);
  return out;
}

bool same_bytes(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST_F(cryptomatte_cli, channels_do_not_depend_on_threads_or_tiles) {
  const std::vector<std::string> base = {"--aovs",          "cryptomatte", "--filter",
                                         "blackman-harris", "--spp",       "3"};
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.begin(), base.begin(), base.end());
    return extra;
  };
  const image one = render(full_, dir_, "t1.exr", with({"--threads", "1", "--tile-size", "5"}));
  const image two = render(full_, dir_, "t2.exr", with({"--threads", "2", "--tile-size", "5"}));
  const std::vector<float> reference = crypto_channels(one, 0, size);
  ASSERT_EQ(reference.size(), size_t(size) * size * 24);
  EXPECT_TRUE(same_bytes(reference, crypto_channels(two, 0, size)));
  const image other_tiles = render(full_, dir_, "t3.exr", with({"--threads", "2", "--tile-size", "16"}));
  EXPECT_TRUE(same_bytes(reference, crypto_channels(other_tiles, 0, size)));
  for (int band = 0; band < 3; ++band) {
    const image part =
        render(full_, dir_, "band.exr",
               with({"--threads", "2", "--tile-size", "5", "--band", std::to_string(band) + "/3"}));
    const int y0 = band * size / 3, y1 = (band + 1) * size / 3;
    ASSERT_EQ(part.spec.y, y0);
    EXPECT_TRUE(same_bytes(crypto_channels(one, y0, y1), crypto_channels(part, y0, y1))) << "band " << band;
  }
  // Some pixels hold two or more ids: the comparison covers the border slots, not only flat areas.
  size_t mixed = 0;
  for (size_t p = 0; p < one.count(); ++p) mixed += one.at(p, "CryptoObject00.A") > 0.0f;
  EXPECT_GE(mixed, 20u);
}

TEST_F(cryptomatte_cli, depth_option_sets_the_number_of_ranks) {
  const image im = render(full_, dir_, "d.exr", {"--aovs", "crypto_material", "--cryptomatte-depth", "3"});
  std::vector<std::string> expected;
  for (const char* set : {"00", "01"})
    for (const char* c : {".A", ".B", ".G", ".R"})
      expected.push_back(std::string("CryptoMaterial") + set + c);
  std::vector<std::string> names = im.spec.channelnames;
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, expected);
  for (size_t p = 0; p < im.count(); ++p) {
    EXPECT_EQ(im.at(p, "CryptoMaterial01.B"), 0.0f);  // rank 3 does not exist
    EXPECT_EQ(im.at(p, "CryptoMaterial01.A"), 0.0f);
  }
  auto result = run_kiln({"render", full_, "-o", dir_ + "/bad.exr", "--cryptomatte-depth", "0"});
  EXPECT_EQ(result.exit_code, 2);
}

// A real asset: the manifest holds the names of exactly the glTF nodes with a mesh (read from the
// file here), and every pixel's coverage sums to its alpha within 1e-5 (float channels).
TEST(cryptomatte_asset_cli, toy_car_decodes_to_its_alpha) {
  const std::string asset = std::string(KILN_SHARED_ASSETS) + "/ToyCar/glTF/ToyCar.gltf";
  if (!std::ifstream(asset)) GTEST_SKIP() << asset << " is not available";
  nlohmann::json doc;
  std::ifstream(asset) >> doc;
  nlohmann::json expected;
  for (const nlohmann::json& node : doc["nodes"])
    if (node.contains("mesh")) expected[node["name"].get<std::string>()] = hex8(id_bits(node["name"]));
  const std::string dir = scratch_folder("cryptomatte_asset");
  const image im =
      render(asset, dir, "car.exr", {"--aovs", "beauty,cryptomatte", "--filter", "gaussian", "--spp", "4"});
  EXPECT_EQ(nlohmann::json::parse(layer_metadata(im.spec, "CryptoObject").at("manifest")), expected);
  float worst = 0.0f;
  size_t partial = 0;
  for (size_t p = 0; p < im.count(); ++p) {
    worst = std::max({worst, std::abs(coverage_sum(im, p, "CryptoObject") - im.at(p, "A")),
                      std::abs(coverage_sum(im, p, "CryptoMaterial") - im.at(p, "A"))});
    partial += im.at(p, "CryptoObject00.G") < 0.999f && im.at(p, "CryptoObject00.G") > 0.0f;
  }
  EXPECT_LE(worst, 1e-5f);
  EXPECT_GT(partial, 0u);
  std::printf("ToyCar %dx%d: max |coverage sum - alpha| %.3g, %zu pixels with a partial rank 0\n",
              im.spec.width, im.spec.height, worst, partial);
}

// A plane facing the camera at distance 5: planar depth is 5 everywhere, ray distance 5/cos θ with
// θ the angle between the pixel centre's ray and the view axis.
TEST(depth_mode_cli, planar_depth_of_a_facing_plane_is_constant) {
  const std::string dir = scratch_folder("depth_mode");
  gltf_builder b;
  b.add_node({{"mesh", b.add_mesh({{-50, -50, -5}, {50, -50, -5}, {50, 50, -5}, {-50, 50, -5}},
                                  {0, 1, 2, 0, 2, 3})}});
  const double yfov = 0.9;
  b.add_camera({{"type", "perspective"}, {"perspective", {{"yfov", yfov}, {"znear", 0.1}}}});
  b.add_node({{"camera", 0}});
  const std::string scene = dir + "/plane.gltf";
  b.write(scene);
  const int w = 40, h = 30;
  auto z_of = [&](const std::string& mode) {
    auto result = run_kiln({"render", scene, "-o", dir + "/" + mode + ".exr", "--width", std::to_string(w),
                            "--height", std::to_string(h), "-q", "--aovs", "Z", "--depth-mode", mode});
    EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
    return read(dir + "/" + mode + ".exr");
  };
  const image planar = z_of("planar"), distance = z_of("distance");
  EXPECT_EQ(planar.spec.get_string_attribute("kiln/depth"), "planar depth");
  EXPECT_EQ(distance.spec.get_string_attribute("kiln/depth"), "ray distance");
  const double t = std::tan(yfov / 2), aspect = double(w) / h;
  double planar_error = 0.0, distance_error = 0.0, distance_spread = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * w + x;
      const double dx = ((x + 0.5) / w * 2 - 1) * t * aspect, dy = (1 - (y + 0.5) / h * 2) * t;
      const double expected_distance = 5.0 * std::sqrt(dx * dx + dy * dy + 1.0);
      planar_error = std::max(planar_error, std::abs(planar.at(p, "Z") - 5.0));
      distance_error = std::max(distance_error, std::abs(distance.at(p, "Z") - expected_distance));
      distance_spread = std::max(distance_spread, distance.at(p, "Z") - 5.0);
    }
  EXPECT_LE(planar_error, 5e-5);  // 1e-5 relative: float distances and cosines
  EXPECT_LE(distance_error, 5e-5);
  EXPECT_GT(distance_spread, 0.5);  // the corners are much farther along the ray
}

// The light split of the demo scenes: the three parts sum to R G B (float channels; the parts and the
// beauty are folded separately, so they agree to float rounding, 1e-5 relative asserted), for each
// filter and for adaptive sampling.
TEST(light_split_cli, parts_sum_to_the_beauty) {
  const std::string dir = scratch_folder("light_split");
  const std::vector<std::vector<std::string>> samplings = {
      {"--filter", "box", "--spp", "4"},
      {"--filter", "blackman-harris", "--spp", "2", "--sampler", "random"},
      {"--adaptive-threshold", "0.1", "--adaptive-depth", "2"},
  };
  for (const char* name : {"glass_showcase", "cornell_box"}) {
    const std::string scene = std::string(KILN_SOURCE_DIR) + "/scenes/" + name + ".gltf";
    for (const auto& sampling : samplings) {
      std::vector<std::string> args = {"--aovs", "beauty,direct,reflection,refraction"};
      args.insert(args.end(), sampling.begin(), sampling.end());
      const image im = render(scene, dir, "split.exr", args);
      float worst = 0.0f;
      double reflected = 0.0, refracted = 0.0;
      for (size_t p = 0; p < im.count(); ++p)
        for (const char* c : {".R", ".G", ".B"}) {
          const float beauty = im.at(p, std::string(c).substr(1));
          const float parts = im.at(p, std::string("direct") + c) + im.at(p, std::string("reflection") + c) +
                              im.at(p, std::string("refraction") + c);
          worst = std::max(worst, std::abs(parts - beauty) / std::max(1.0f, std::abs(beauty)));
          reflected += im.at(p, std::string("reflection") + c);
          refracted += im.at(p, std::string("refraction") + c);
        }
      const std::string what = std::string(name) + " " + sampling[0] + " " + sampling[1];
      EXPECT_LE(worst, 1e-5f) << what;
      EXPECT_GT(reflected, 0.0) << what;  // both scenes hold mirrors
      EXPECT_GT(refracted, 0.0) << what;  // and glass
      std::printf("%s: max relative |direct + reflection + refraction - beauty| %.3g\n", what.c_str(), worst);
    }
  }
}

// Asking for the split changes no beauty byte, and the split channels do not depend on threads or
// tiles either.
TEST(light_split_cli, beauty_bytes_stay_and_split_is_deterministic) {
  const std::string dir = scratch_folder("light_split_bytes");
  const std::string scene = std::string(KILN_SOURCE_DIR) + "/scenes/glass_showcase.gltf";
  const std::vector<std::string> base = {"--filter", "tent", "--spp", "2", "--tile-size", "6"};
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.end(), base.begin(), base.end());
    return extra;
  };
  const image plain = render(scene, dir, "plain.exr", with({"--aovs", "beauty"}));
  const image split = render(scene, dir, "split.exr",
                             with({"--aovs", "beauty,direct,reflection,refraction", "--threads", "1"}));
  const image split2 = render(scene, dir, "split2.exr",
                              with({"--aovs", "beauty,direct,reflection,refraction", "--threads", "2"}));
  const image band = render(scene, dir, "band.exr",
                            with({"--aovs", "beauty,direct,reflection,refraction", "--band", "1/2"}));
  size_t differing = 0, split_differing = 0, band_differing = 0;
  for (size_t p = 0; p < plain.count(); ++p) {
    for (const char* c : {"R", "G", "B", "A"}) differing += plain.at(p, c) != split.at(p, c);
    for (const char* part : {"direct", "reflection", "refraction"})
      for (const char* c : {".R", ".G", ".B"}) {
        const std::string channel = std::string(part) + c;
        split_differing += split.at(p, channel) != split2.at(p, channel);
        const size_t y = p / size_t(size);
        if (int(y) >= band.spec.y && int(y) < band.spec.y + band.spec.height)
          band_differing += split.at(p, channel) != band.at(p - size_t(band.spec.y) * size, channel);
      }
  }
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(split_differing, 0u);
  EXPECT_EQ(band_differing, 0u);
}

// A rough opaque quad seen partly through a half-transparent BLEND quad: nothing is reflected or
// refracted, so reflection and refraction are exactly 0 and direct is the beauty, bit for bit.
TEST(light_split_cli, rough_surfaces_are_all_direct) {
  const std::string dir = scratch_folder("light_split_rough");
  gltf_builder b;
  const int rough =
      b.add_material({{"pbrMetallicRoughness", {{"roughnessFactor", 1.0}, {"metallicFactor", 0.0}}}});
  const int veil = b.add_material(
      {{"alphaMode", "BLEND"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.2, 0.9, 0.3, 0.5}}, {"roughnessFactor", 1.0}, {"metallicFactor", 0.0}}}});
  b.add_node(
      {{"mesh", b.add_mesh({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, {0, 1, 2, 0, 2, 3}, rough)}});
  b.add_node({{"mesh", b.add_mesh({{-0.5f, -2, 0.5f}, {2, -2, 0.5f}, {2, 0.5f, 0.5f}}, {0, 1, 2}, veil)}});
  b.add_camera({{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}});
  b.add_node({{"camera", 0}, {"translation", {0, 0, 4}}});
  const std::string scene = dir + "/rough.gltf";
  b.write(scene);
  const image im = render(scene, dir, "rough.exr",
                          {"--aovs", "beauty,direct,reflection,refraction", "--spp", "4", "--filter",
                           "gaussian", "--background", "0.1,0.2,0.3"});
  size_t lit = 0;
  for (size_t p = 0; p < im.count(); ++p)
    for (const char* c : {"R", "G", "B"}) {
      EXPECT_EQ(im.at(p, std::string("direct.") + c), im.at(p, c)) << p;
      EXPECT_EQ(im.at(p, std::string("reflection.") + c), 0.0f) << p;
      EXPECT_EQ(im.at(p, std::string("refraction.") + c), 0.0f) << p;
      lit += im.at(p, c) > 0.0f;
    }
  EXPECT_GT(lit, im.count());  // the scene is not black
}

}  // namespace
}  // namespace kiln
