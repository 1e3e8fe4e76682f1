#include "io/gltf/gltf_schema_check.h"

#include <cstdint>
#include <limits>
#include <vector>

#include "core/error.h"
#include "core/message_text.h"
#include "io/gltf/gltf_common.h"

namespace kiln::gltf_internal {
namespace {

using json = nlohmann::json;

constexpr int64_t int_max = std::numeric_limits<int32_t>::max();     // what tinygltf's int fields hold
constexpr int64_t wide_max = std::numeric_limits<int64_t>::max();    // its size_t fields
constexpr int64_t no_minimum = std::numeric_limits<int32_t>::min();  // enums: validation names them

// A collection an index points into: where it sits in the document and how messages name it.
struct collection {
  std::vector<const char*> location;  // keys from the root
  const char* name;                   // "/<name>/7 does not exist (file has 3 <noun>)"
  const char* noun = name;
};

// One integer property: a pattern of keys from the root ("*": every element or member), the
// collection it indexes (none for a plain integer) and its bounds.
struct integer_rule {
  std::string pattern;
  const collection* target = nullptr;
  int64_t min = 0;
  int64_t max = int_max;
};

const collection accessors{{"accessors"}, "accessors"}, buffers{{"buffers"}, "buffers"},
    buffer_views{{"bufferViews"}, "bufferViews"}, cameras{{"cameras"}, "cameras"},
    images{{"images"}, "images"}, materials{{"materials"}, "materials"}, meshes{{"meshes"}, "meshes"},
    nodes{{"nodes"}, "nodes"}, samplers{{"samplers"}, "samplers"}, scenes{{"scenes"}, "scenes"},
    skins{{"skins"}, "skins"}, textures{{"textures"}, "textures"},
    lights{{"extensions", "KHR_lights_punctual", "lights"}, "lights"},
    quadrics{{"extensions", "KILN_quadric", "primitives"},
             "extensions/KILN_quadric/primitives",
             "quadric definitions"},
    variants{{"extensions", "KHR_materials_variants", "variants"},
             "extensions/KHR_materials_variants/variants",
             "variants"};

std::vector<integer_rule> make_rules() {
  std::vector<integer_rule> rules = {
      {"accessors/*/bufferView", &buffer_views},
      {"accessors/*/byteOffset", nullptr, 0, wide_max},
      {"accessors/*/componentType", nullptr, no_minimum},
      {"accessors/*/count", nullptr, 1, wide_max},
      {"accessors/*/sparse/count", nullptr, 1},
      {"accessors/*/sparse/indices/bufferView", &buffer_views},
      {"accessors/*/sparse/indices/byteOffset"},
      {"accessors/*/sparse/indices/componentType", nullptr, no_minimum},
      {"accessors/*/sparse/values/bufferView", &buffer_views},
      {"accessors/*/sparse/values/byteOffset"},
      {"animations/*/channels/*/sampler"},  // indexes its own animation's samplers: validation checks it
      {"animations/*/channels/*/target/node", &nodes},
      {"animations/*/samplers/*/input", &accessors},
      {"animations/*/samplers/*/output", &accessors},
      {"bufferViews/*/buffer", &buffers},
      {"bufferViews/*/byteOffset", nullptr, 0, wide_max},
      {"bufferViews/*/byteLength", nullptr, 1, wide_max},
      {"bufferViews/*/target", nullptr, no_minimum},
      // Extension objects reach the loader as tinygltf Values, whose integers are ints too.
      {"bufferViews/*/extensions/EXT_meshopt_compression/buffer", &buffers},
      {"bufferViews/*/extensions/EXT_meshopt_compression/byteOffset"},
      {"bufferViews/*/extensions/EXT_meshopt_compression/byteLength"},
      {"bufferViews/*/extensions/EXT_meshopt_compression/byteStride"},
      {"bufferViews/*/extensions/EXT_meshopt_compression/count"},
      {"images/*/bufferView", &buffer_views},
      {"meshes/*/primitives/*/attributes/*", &accessors},
      {"meshes/*/primitives/*/indices", &accessors},
      {"meshes/*/primitives/*/material", &materials},
      {"meshes/*/primitives/*/mode", nullptr, no_minimum},
      {"meshes/*/primitives/*/targets/*/*", &accessors},
      {"meshes/*/primitives/*/extensions/KHR_materials_variants/mappings/*/material", &materials},
      {"meshes/*/primitives/*/extensions/KHR_materials_variants/mappings/*/variants/*", &variants},
      {"nodes/*/camera", &cameras},
      {"nodes/*/children/*", &nodes},
      {"nodes/*/skin", &skins},
      {"nodes/*/mesh", &meshes},
      {"nodes/*/extensions/KHR_lights_punctual/light", &lights},
      {"nodes/*/extensions/KILN_quadric/primitive", &quadrics},
      {"nodes/*/extensions/KILN_quadric/material", &materials},
      {"nodes/*/extensions/EXT_mesh_gpu_instancing/attributes/*", &accessors},
      {"samplers/*/magFilter", nullptr, no_minimum},
      {"samplers/*/minFilter", nullptr, no_minimum},
      {"samplers/*/wrapS", nullptr, no_minimum},
      {"samplers/*/wrapT", nullptr, no_minimum},
      {"scene", &scenes},
      {"scenes/*/nodes/*", &nodes},
      {"skins/*/inverseBindMatrices", &accessors},
      {"skins/*/skeleton", &nodes},
      {"skins/*/joints/*", &nodes},
      {"textures/*/sampler", &samplers},
      {"textures/*/source", &images},
      {"textures/*/extensions/EXT_texture_webp/source", &images},
      // Never decoded, but an index all the same: one past the images is a broken file.
      {"textures/*/extensions/KHR_texture_basisu/source", &images},
  };
  // Every textureInfo a material may hold, with KHR_texture_transform's texCoord override.
  for (const char* info :
       {"pbrMetallicRoughness/baseColorTexture", "pbrMetallicRoughness/metallicRoughnessTexture",
        "normalTexture", "occlusionTexture", "emissiveTexture",
        "extensions/KHR_materials_transmission/transmissionTexture",
        "extensions/KHR_materials_volume/thicknessTexture",
        "extensions/KHR_materials_specular/specularTexture",
        "extensions/KHR_materials_specular/specularColorTexture"}) {
    const std::string at = std::string("materials/*/") + info;
    rules.push_back({at + "/index", &textures});
    rules.push_back({at + "/texCoord"});
    rules.push_back({at + "/extensions/KHR_texture_transform/texCoord"});
  }
  return rules;
}

std::vector<std::string> split(const std::string& pattern) {
  std::vector<std::string> keys;
  size_t start = 0;
  while (true) {
    const size_t end = pattern.find('/', start);
    keys.push_back(pattern.substr(start, end - start));
    if (end == std::string::npos) return keys;
    start = end + 1;
  }
}

// How many elements the collection has (0 when the document lacks it).
size_t collection_size(const json& doc, const collection& c) {
  const json* at = &doc;
  for (const char* key : c.location) {
    if (!at->is_object()) return 0;
    auto it = at->find(key);
    if (it == at->end()) return 0;
    at = &*it;
  }
  return at->is_array() ? at->size() : 0;
}

// The last key of a pointer: the property's name in messages.
std::string property_name(const std::string& where) { return where.substr(where.rfind('/') + 1); }

void check_value(const json& doc, const json& value, const integer_rule& rule, const std::string& path,
                 const std::string& where) {
  const std::string what = rule.target ? "an index" : property_name(where);
  if (!value.is_number_integer())
    throw input_error(path, where, what + " must be an integer, got " + shown(value.dump()));
  // Above int64's range only an unsigned integer remains; every such value is out of bounds.
  const bool huge = value.is_number_unsigned() && value.get<uint64_t>() > uint64_t(wide_max);
  const int64_t v = huge ? wide_max : value.get<int64_t>();
  if (rule.target) {
    if (v < 0)
      throw input_error(
          path, where,
          "index " + value.dump() + " is negative (glTF leaves a reference out rather than use -1)");
    const size_t size = collection_size(doc, *rule.target);
    if (huge || uint64_t(v) >= size)
      throw input_error(path, where,
                        std::string("/") + rule.target->name + "/" + value.dump() +
                            " does not exist (file has " + std::to_string(size) + " " + rule.target->noun +
                            ")");
    return;
  }
  if (v < rule.min)
    throw input_error(path, where,
                      what + " must be at least " + std::to_string(rule.min) + ", got " + value.dump());
  if (huge || v > rule.max)
    throw input_error(
        path, where,
        what + " is " + value.dump() + ", larger than kiln reads (at most " + std::to_string(rule.max) + ")");
}

// Visits every value the pattern's keys reach from `at`, in document order.
void visit(const json& doc, const json& at, const std::vector<std::string>& keys, size_t depth,
           const std::string& where, const integer_rule& rule, const std::string& path) {
  if (depth == keys.size()) return check_value(doc, at, rule, path, where);
  const std::string& key = keys[depth];
  if (key == "*" && at.is_array()) {
    for (size_t i = 0; i < at.size(); ++i)
      visit(doc, at[i], keys, depth + 1, pointer_join(where, int64_t(i)), rule, path);
  } else if (key == "*" && at.is_object()) {
    for (auto it = at.begin(); it != at.end(); ++it)
      visit(doc, it.value(), keys, depth + 1, pointer_join(where, it.key()), rule, path);
  } else if (key != "*" && at.is_object()) {
    auto it = at.find(key);
    if (it != at.end()) visit(doc, *it, keys, depth + 1, pointer_join(where, key), rule, path);
  }
}

const json* member(const json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

}  // namespace

void check_integer_properties(const json& doc, const std::string& path) {
  static const std::vector<integer_rule> rules = make_rules();
  for (const integer_rule& rule : rules) visit(doc, doc, split(rule.pattern), 0, "", rule, path);
}

void check_camera_numbers(const json& doc, const std::string& path) {
  const json* list = member(doc, "cameras");
  if (!list || !list->is_array()) return;
  for (size_t c = 0; c < list->size(); ++c) {
    const json* perspective = member((*list)[c], "perspective");
    if (!perspective) continue;
    const std::string at = pointer_join(pointer("cameras", int64_t(c)), "perspective");
    if (const json* aspect = member(*perspective, "aspectRatio"))
      if (!aspect->is_number() || !(aspect->get<double>() > 0.0))
        throw input_error(path, pointer_join(at, "aspectRatio"),
                          "aspectRatio must be a number greater than 0, got " + shown(aspect->dump()));
    const json* zfar = member(*perspective, "zfar");
    if (!zfar) continue;
    const json* znear = member(*perspective, "znear");
    const double near_value = znear && znear->is_number() ? znear->get<double>() : 0.0;
    if (!zfar->is_number() || !(zfar->get<double>() > 0.0) || !(zfar->get<double>() > near_value))
      throw input_error(path, pointer_join(at, "zfar"),
                        "zfar must be greater than znear and 0, got " + shown(zfar->dump()));
  }
}

}  // namespace kiln::gltf_internal
