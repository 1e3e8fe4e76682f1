// Which arbitrary output variables (AOVs) a render produces and writes, parsed from `--aovs`.
// Depends on core only.
#pragma once

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>

#include "core/aov_id.h"

namespace kiln {

// What Z holds: the ray distance from the camera, or the planar depth along the view axis (the
// ray distance times the cosine between the ray and the view direction).
enum class depth_mode { distance, planar };

// The Cryptomatte specification's suggested default: 6 ranks, three RGBA channel sets.
constexpr int default_cryptomatte_depth = 6;
constexpr int max_cryptomatte_depth = 32;

static_assert(aov_count <= 32, "aov_set keeps one bit per AOV");
constexpr uint32_t aov_bit(aov a) { return uint32_t(1) << int(a); }

// Which AOVs a render writes (render/aov_table.h says what each holds), and how. The default is
// what kiln has always written: beauty, Z and N.
struct aov_set {
  uint32_t bits = aov_bit(aov::beauty) | aov_bit(aov::depth) | aov_bit(aov::normal);
  bool has(aov a) const { return (bits & aov_bit(a)) != 0; }
  void set(aov a, bool on = true) { bits = on ? bits | aov_bit(a) : bits & ~aov_bit(a); }
  // Cryptomatte ranks (id, coverage pairs) kept per pixel.
  int crypto_depth = default_cryptomatte_depth;
  // What Z holds.
  depth_mode depth_kind = depth_mode::distance;
};

// Parses a comma-separated list of the AOV table's names, and cryptomatte for both Cryptomatte
// layers (case-sensitive, each at most once, at least one). Returns empty and sets *bad to the offending item
// otherwise.
std::optional<aov_set> parse_aov_list(const std::string& text, std::string* bad);

// True for the AOVs of the light split by first event (shade/path_record.h's record_direct and
// record_branch file them).
inline bool is_light_split(aov a) { return a == aov::direct || a == aov::reflection || a == aov::refraction; }

// True when some output needs the light split.
inline bool wants_light_split(const aov_set& a) {
  return a.has(aov::direct) || a.has(aov::reflection) || a.has(aov::refraction);
}

// True when some output needs the camera path's passes (shade/path_record.h's camera_passes): a
// filtered AOV other than the beauty, the light split and the light groups.
bool wants_camera_passes(const aov_set& a);

// The set of exactly these AOVs, with the default Cryptomatte depth and Z.
aov_set aov_set_of(std::initializer_list<aov> list);

// The canonical comma-separated list, in channel order: "beauty,Z,N" for the default (the
// cryptomatte shorthand is listed as crypto_object,crypto_material).
std::string aov_list_name(const aov_set& aovs);

// "distance" or "planar"; empty for anything else.
std::optional<depth_mode> parse_depth_mode(const std::string& name);

}  // namespace kiln
