// MurmurHash3_x86_32 against the reference implementation's published test vectors, and the
// Cryptomatte conversion, keys and manifest against the values in the Cryptomatte specification.
#include "io/exr/cryptomatte.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "io/exr/murmur3.h"

namespace kiln {
namespace {

TEST(murmur3, known_answers) {
  using namespace std::string_view_literals;
  struct vector {
    std::string_view key;
    uint32_t seed, hash;
  };
  // SMHasher's MurmurHash3_x86_32, as collected in the widely used test vector list: empty input
  // with three seeds, every tail length (1 to 3 bytes) and whole blocks.
  const vector vectors[] = {
      {""sv, 0, 0x00000000u},
      {""sv, 1, 0x514e28b7u},
      {""sv, 0xffffffffu, 0x81f16f39u},
      {"\0\0\0\0"sv, 0, 0x2362f9deu},
      {"\xff\xff\xff\xff"sv, 0, 0x76293b50u},
      {"\x21\x43\x65\x87"sv, 0, 0xf55b516bu},
      {"\x21\x43\x65\x87"sv, 0x5082edeeu, 0x2362f9deu},
      {"\x21\x43\x65"sv, 0, 0x7e4a8634u},
      {"\x21\x43"sv, 0, 0xa0f7b07au},
      {"\x21"sv, 0, 0x72661cf4u},
      {"\0\0\0"sv, 0, 0x85f0b427u},
      {"\0\0"sv, 0, 0x30f4c306u},
      {"\0"sv, 0, 0x514e28b7u},
      {"aaaa"sv, 0x9747b28cu, 0x5a97808au},
      {"aaa"sv, 0x9747b28cu, 0x283e0130u},
      {"aa"sv, 0x9747b28cu, 0x5d211726u},
      {"a"sv, 0x9747b28cu, 0x7fa09ea6u},
      {"abcd"sv, 0x9747b28cu, 0xf0478627u},
      {"abc"sv, 0x9747b28cu, 0xc84a62ddu},
      {"ab"sv, 0x9747b28cu, 0x74875592u},
      {"Hello, world!"sv, 0x9747b28cu, 0x24884cbau},
      {"The quick brown fox jumps over the lazy dog"sv, 0x9747b28cu, 0x2fa826cdu},
  };
  for (const vector& v : vectors)
    EXPECT_EQ(murmur3_x86_32(v.key, v.seed), v.hash) << "'" << v.key << "' seed " << v.seed;
}

TEST(cryptomatte, ids_match_the_specification_manifest_example) {
  // The specification's example manifest: {"bunny":"13851a76", "default":"42c9679f"}.
  EXPECT_EQ(cryptomatte_id("bunny"), 0x13851a76u);
  EXPECT_EQ(cryptomatte_id("default"), 0x42c9679fu);
}

TEST(cryptomatte, conversion_clamps_the_exponent_and_keeps_sign_and_mantissa) {
  // Exponent 0 (zero, denormals) becomes 1 and 255 (infinities, NaNs) becomes 254.
  EXPECT_EQ(cryptomatte_id_bits(0x00000000u), 0x00800000u);
  EXPECT_EQ(cryptomatte_id_bits(0x80000001u), 0x80800001u);
  EXPECT_EQ(cryptomatte_id_bits(0x7f800000u), 0x7f000000u);
  EXPECT_EQ(cryptomatte_id_bits(0xffffffffu), 0xff7fffffu);
  EXPECT_EQ(cryptomatte_id_bits(0x3f800000u), 0x3f800000u);  // 1.0f passes unchanged
  for (uint32_t h : {0u, 0x007fffffu, 0x7f800001u, 0xff800000u, 0x12345678u, 0x80000000u}) {
    const float f = cryptomatte_id_float(h);
    EXPECT_TRUE(std::isnormal(f)) << std::hex << h;
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    EXPECT_EQ(bits, cryptomatte_id_bits(h));
  }
}

TEST(cryptomatte, keys_are_seven_hex_digits_of_the_layer_name_hash) {
  // The specification only suggests a hash of the layer name (its example keys are arbitrary).
  for (const char* layer : {"CryptoObject", "CryptoMaterial"}) {
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", murmur3_x86_32(layer));
    EXPECT_EQ(cryptomatte_key(layer), std::string(hex, 7)) << layer;
  }
  EXPECT_NE(cryptomatte_key("CryptoObject"), cryptomatte_key("CryptoMaterial"));
}

// A render layer's manifests list its own objects and their materials; the held-out instances keep
// their ids in the table (nothing reads them) but are not named.
TEST(cryptomatte, a_render_layer_names_its_own_objects_and_materials_only) {
  scene world;
  world.node_names = {"car", "wall"};
  instance car, wall;
  car.node = 0;
  car.material = 0;
  wall.node = 1;
  wall.material = 1;
  wall.holdout = holdout_kind::unseen;
  world.instances = {car, wall};
  material paint, plaster;
  paint.name = "paint";
  paint.source_index = 0;
  plaster.name = "plaster";
  plaster.source_index = 1;
  world.materials = {paint, plaster};
  const cryptomatte_layer objects = cryptomatte_objects(world);
  EXPECT_EQ(objects.manifest, (std::map<std::string, uint32_t>{{"car", cryptomatte_id("car")}}));
  ASSERT_EQ(objects.id_by_key.size(), 2u);
  EXPECT_EQ(objects.id_by_key[1], cryptomatte_id("wall"));
  const cryptomatte_layer materials = cryptomatte_materials(world);
  EXPECT_EQ(materials.manifest, (std::map<std::string, uint32_t>{{"paint", cryptomatte_id("paint")}}));
  world.instances[1].holdout = holdout_kind::none;  // not a layer: every material is named
  EXPECT_EQ(cryptomatte_materials(world).manifest.size(), 2u);
}

TEST(cryptomatte, layers_name_nodes_and_materials_with_fallbacks) {
  scene world;
  world.node_names = {"car", "", "wheel"};
  instance a, b, c;
  a.node = 0;
  b.node = 1;
  c.node = 2;
  world.instances = {a, b, c, c};
  material named, unnamed, fallback;
  named.name = "paint";
  named.source_index = 0;
  unnamed.source_index = 2;
  fallback.name = "default";
  fallback.source_index = 3;
  world.materials = {named, unnamed, fallback};

  const cryptomatte_layer objects = cryptomatte_objects(world);
  EXPECT_EQ(objects.name, "CryptoObject");
  ASSERT_EQ(objects.id_by_key.size(), 3u);
  EXPECT_EQ(objects.id_by_key[0], cryptomatte_id("car"));
  EXPECT_EQ(objects.id_by_key[1], cryptomatte_id("node1"));
  EXPECT_EQ(objects.id_by_key[2], cryptomatte_id("wheel"));
  const std::map<std::string, uint32_t> expected_objects = {
      {"car", cryptomatte_id("car")}, {"node1", cryptomatte_id("node1")}, {"wheel", cryptomatte_id("wheel")}};
  EXPECT_EQ(objects.manifest, expected_objects);

  const cryptomatte_layer materials = cryptomatte_materials(world);
  ASSERT_EQ(materials.id_by_key.size(), 4u);
  EXPECT_EQ(materials.id_by_key[0], cryptomatte_id("paint"));
  EXPECT_EQ(materials.id_by_key[2], cryptomatte_id("material2"));
  EXPECT_EQ(materials.id_by_key[3], cryptomatte_id("default"));
  EXPECT_EQ(materials.manifest.size(), 3u);

  const nlohmann::json manifest = nlohmann::json::parse(cryptomatte_manifest_json(materials));
  ASSERT_EQ(manifest.size(), 3u);
  EXPECT_EQ(manifest.at("default"), "42c9679f");
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", cryptomatte_id("paint"));
  EXPECT_EQ(manifest.at("paint"), hex);

  const auto attributes = cryptomatte_attributes(objects);
  ASSERT_EQ(attributes.size(), 4u);
  const std::string prefix = "cryptomatte/" + cryptomatte_key("CryptoObject") + "/";
  EXPECT_EQ(attributes[0], std::make_pair(prefix + "name", std::string("CryptoObject")));
  EXPECT_EQ(attributes[1].second, "MurmurHash3_32");
  EXPECT_EQ(attributes[2].second, "uint32_to_float32");
  EXPECT_EQ(attributes[3].first, prefix + "manifest");
}

}  // namespace
}  // namespace kiln
