#include "render/aov_list.h"

#include <sstream>

namespace kiln {

namespace {

struct aov_name {
  const char* name;
  bool aov_set::*flag;
};

// Channel order in the EXR file.
constexpr aov_name aov_names[] = {
    {"beauty", &aov_set::beauty},
    {"Z", &aov_set::depth},
    {"N", &aov_set::normal},
    {"P", &aov_set::position},
    {"albedo", &aov_set::albedo},
    {"uv", &aov_set::uv},
    {"id", &aov_set::ids},
    {"motion", &aov_set::motion},
    {"crypto_object", &aov_set::crypto_object},
    {"crypto_material", &aov_set::crypto_material},
    {"direct", &aov_set::direct},
    {"reflection", &aov_set::reflection},
    {"refraction", &aov_set::refraction},
    {"lightgroups", &aov_set::light_groups},
    {"albedo_filtered", &aov_set::albedo_filtered},
    {"N_filtered", &aov_set::normal_filtered},
    {"diffuse", &aov_set::diffuse},
    {"specular", &aov_set::specular},
    {"shadow", &aov_set::shadow},
};

// Shorthand for both Cryptomatte layers.
constexpr const char* cryptomatte_name = "cryptomatte";

}  // namespace

std::optional<aov_set> parse_aov_list(const std::string& text, std::string* bad) {
  aov_set aovs;
  for (const aov_name& a : aov_names) aovs.*a.flag = false;
  std::istringstream in(text);
  std::string item;
  bool any = false;
  while (std::getline(in, item, ',')) {
    if (item == cryptomatte_name) {
      if (aovs.crypto_object || aovs.crypto_material) {
        if (bad) *bad = item + " (given twice)";
        return std::nullopt;
      }
      aovs.crypto_object = aovs.crypto_material = true;
      any = true;
      continue;
    }
    const aov_name* found = nullptr;
    for (const aov_name& a : aov_names)
      if (item == a.name) found = &a;
    if (!found || aovs.*found->flag) {
      if (bad) *bad = found ? item + " (given twice)" : "'" + item + "'";
      return std::nullopt;
    }
    aovs.*found->flag = true;
    any = true;
  }
  // getline drops a trailing empty item, so "beauty," needs its own check.
  if (!any || text.back() == ',') {
    if (bad) *bad = "an empty name";
    return std::nullopt;
  }
  return aovs;
}

std::string aov_list_name(const aov_set& aovs) {
  std::string out;
  for (const aov_name& a : aov_names)
    if (aovs.*a.flag) out += (out.empty() ? "" : ",") + std::string(a.name);
  return out;
}

std::optional<depth_mode> parse_depth_mode(const std::string& name) {
  if (name == "distance") return depth_mode::distance;
  if (name == "planar") return depth_mode::planar;
  return std::nullopt;
}

}  // namespace kiln
