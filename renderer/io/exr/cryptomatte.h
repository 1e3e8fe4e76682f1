// Cryptomatte ids, manifests and header attributes (Psyop's Cryptomatte specification 1.1):
// names hashed with MurmurHash3_x86_32 (seed 0), each hash turned into a float by clamping its
// exponent to [1, 254] (no denormals, zeros, infinities or NaNs), the manifest a JSON object of
// name -> the float's bits as 8 hex digits. Depends on core and scene only.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace kiln {

constexpr const char* crypto_object_layer_name = "CryptoObject";
constexpr const char* crypto_material_layer_name = "CryptoMaterial";

// One Cryptomatte layer's ids: what the renderer accumulates and the manifest that names them.
struct cryptomatte_layer {
  std::string name;                          // the channel prefix, e.g. "CryptoObject"
  std::vector<uint32_t> id_by_key;           // glTF node index or material source index -> id bits
  std::map<std::string, uint32_t> manifest;  // every name the scene can show -> its id bits
};

// The specification's uint32_to_float32 conversion, as the bits of the float.
uint32_t cryptomatte_id_bits(uint32_t hash);
float cryptomatte_id_float(uint32_t hash);

// The id of a name: the converted MurmurHash3 of its bytes.
uint32_t cryptomatte_id(std::string_view name);

// The metadata key of a layer: the first 7 hex digits of the MurmurHash3 of its name.
std::string cryptomatte_key(std::string_view layer_name);

// The object name of each glTF node that places geometry: its name, or "node<index>" when unnamed.
// The manifest of a render layer (--only, --holdout) lists the layer's own objects, and its
// materials, only.
cryptomatte_layer cryptomatte_objects(const scene& world);

// The name of each material in the scene: its glTF name, "material<index>" when unnamed; the
// default material (for primitives without one) is "default".
cryptomatte_layer cryptomatte_materials(const scene& world);

// The manifest as JSON text: {"name":"8 hex digits",...}.
std::string cryptomatte_manifest_json(const cryptomatte_layer& layer);

// The header attributes: cryptomatte/<key>/name, /hash, /conversion and /manifest.
std::vector<std::pair<std::string, std::string>> cryptomatte_attributes(const cryptomatte_layer& layer);

}  // namespace kiln
