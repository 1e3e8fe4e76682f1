#include "io/exr/cryptomatte.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>

#include "io/exr/murmur3.h"

namespace kiln {

namespace {

std::string hex8(uint32_t bits) {
  char text[9];
  std::snprintf(text, sizeof text, "%08x", bits);
  return text;
}

// Adds name to the layer's table under key, and to its manifest when listed.
void add_name(cryptomatte_layer& layer, size_t key, const std::string& name, bool listed = true) {
  if (layer.id_by_key.size() <= key) layer.id_by_key.resize(key + 1, 0u);
  const uint32_t id = cryptomatte_id(name);
  layer.id_by_key[key] = id;
  if (listed) layer.manifest[name] = id;
}

}  // namespace

uint32_t cryptomatte_id_bits(uint32_t hash) {
  const uint32_t exponent = std::clamp((hash >> 23) & 0xffu, 1u, 254u);
  return (hash & 0x807fffffu) | (exponent << 23);
}

float cryptomatte_id_float(uint32_t hash) {
  const uint32_t bits = cryptomatte_id_bits(hash);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

uint32_t cryptomatte_id(std::string_view name) { return cryptomatte_id_bits(murmur3_x86_32(name, 0)); }

std::string cryptomatte_key(std::string_view layer_name) {
  return hex8(murmur3_x86_32(layer_name, 0)).substr(0, 7);
}

cryptomatte_layer cryptomatte_objects(const scene& world) {
  cryptomatte_layer layer;
  layer.name = crypto_object_layer_name;
  for (const instance& inst : world.instances) {
    const std::string& name =
        inst.node < world.node_names.size() ? world.node_names[inst.node] : std::string();
    // A render layer's manifest names its own objects only (the others never reach its coverage).
    add_name(layer, inst.node, name.empty() ? "node" + std::to_string(inst.node) : name,
             inst.holdout == holdout_kind::none);
  }
  return layer;
}

cryptomatte_layer cryptomatte_materials(const scene& world) {
  cryptomatte_layer layer;
  layer.name = crypto_material_layer_name;
  // In a render layer, only the materials of the layer's own objects are listed; else all of them.
  const bool render_layer =
      std::any_of(world.instances.begin(), world.instances.end(),
                  [](const instance& inst) { return inst.holdout != holdout_kind::none; });
  std::vector<bool> in_layer(world.materials.size(), !render_layer);
  for (const instance& inst : world.instances)
    if (inst.holdout == holdout_kind::none && inst.material < in_layer.size()) in_layer[inst.material] = true;
  for (size_t i = 0; i < world.materials.size(); ++i) {
    const material& m = world.materials[i];
    if (m.source_index < 0) continue;
    add_name(layer, size_t(m.source_index),
             m.name.empty() ? "material" + std::to_string(m.source_index) : m.name, in_layer[i]);
  }
  return layer;
}

std::string cryptomatte_manifest_json(const cryptomatte_layer& layer) {
  nlohmann::json manifest = nlohmann::json::object();
  for (const auto& [name, id] : layer.manifest) manifest[name] = hex8(id);
  // Replace invalid UTF-8 instead of throwing: a glTF name is meant to be UTF-8 but is not checked.
  return manifest.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::vector<std::pair<std::string, std::string>> cryptomatte_attributes(const cryptomatte_layer& layer) {
  const std::string prefix = "cryptomatte/" + cryptomatte_key(layer.name) + "/";
  return {{prefix + "name", layer.name},
          {prefix + "hash", "MurmurHash3_32"},
          {prefix + "conversion", "uint32_to_float32"},
          {prefix + "manifest", cryptomatte_manifest_json(layer)}};
}

}  // namespace kiln
