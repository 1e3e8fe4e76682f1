// Which arbitrary output variables (AOVs) a render produces and writes, parsed from `--aovs`.
// Depends on core only.
#pragma once

#include <optional>
#include <string>

namespace kiln {

// What Z holds: the ray distance from the camera, or the planar depth along the view axis (the
// ray distance times the cosine between the ray and the view direction).
enum class depth_mode { distance, planar };

// The Cryptomatte specification's suggested default: 6 ranks, three RGBA channel sets.
constexpr int default_cryptomatte_depth = 6;
constexpr int max_cryptomatte_depth = 32;

// One flag per AOV. The default is what kiln has always written: beauty, Z and N.
struct aov_set {
  bool beauty = true;     // R G B A: premultiplied colour, filtered
  bool depth = true;      // Z: ray distance (or planar depth) of the nearest sample
  bool normal = true;     // N.X N.Y N.Z: world shading normal of the nearest sample
  bool position = false;  // P.X P.Y P.Z: world position of the nearest sample's hit
  bool albedo = false;    // albedo.R albedo.G albedo.B: base colour after textures and vertex colours
  bool uv = false;        // uv.U uv.V: TEXCOORD_0 of the nearest sample's hit
  bool ids = false;       // id.object id.material id.instance: glTF node, material, scene instance
  // CryptoObject00.. and CryptoMaterial00..: Cryptomatte ranks of the glTF node and material names.
  bool crypto_object = false;
  bool crypto_material = false;
  // direct.RGB, reflection.RGB, refraction.RGB: the beauty split by first event (shade/whitted.h's
  // light_split), filtered like it; the three sum to R G B.
  bool direct = false;
  bool reflection = false;
  bool refraction = false;
  // lightgroup_<light>.RGB per punctual light (the headlight too), lightgroup_emission.RGB and
  // lightgroup_environment.RGB: the beauty by the source its light came from, through every
  // reflection and refraction, filtered like it; they sum to R G B (render/light_groups.h).
  bool light_groups = false;
  // Cryptomatte ranks (id, coverage pairs) kept per pixel.
  int crypto_depth = default_cryptomatte_depth;
  // What Z holds.
  depth_mode depth_kind = depth_mode::distance;
};

// Parses a comma-separated list of names (beauty, Z, N, P, albedo, uv, id, crypto_object,
// crypto_material, and cryptomatte for both, direct, reflection, refraction, lightgroups; case-sensitive,
// each at most once, at least one). Returns empty and sets *bad to the offending item otherwise.
std::optional<aov_set> parse_aov_list(const std::string& text, std::string* bad);

// True when some output needs the light split.
inline bool wants_light_split(const aov_set& a) { return a.direct || a.reflection || a.refraction; }

// The colour parts filtered beside the beauty, per sample: the light split's three (direct,
// reflection, refraction) when some output needs it, then one per light group when asked for.
inline int beauty_part_count(const aov_set& a, int light_groups) {
  return (wants_light_split(a) ? 3 : 0) + (a.light_groups ? light_groups : 0);
}

// The canonical comma-separated list, in channel order: "beauty,Z,N" for the default (the
// cryptomatte shorthand is listed as crypto_object,crypto_material).
std::string aov_list_name(const aov_set& aovs);

// "distance" or "planar"; empty for anything else.
std::optional<depth_mode> parse_depth_mode(const std::string& name);

}  // namespace kiln
