#include "render/aov_list.h"

#include <sstream>

#include "render/aov_table.h"

namespace kiln {

namespace {

// Shorthand for both Cryptomatte layers.
constexpr const char* cryptomatte_name = "cryptomatte";

}  // namespace

std::optional<aov_set> parse_aov_list(const std::string& text, std::string* bad) {
  aov_set aovs = aov_set_of({});
  std::istringstream in(text);
  std::string item;
  bool any = false;
  while (std::getline(in, item, ',')) {
    if (item == cryptomatte_name) {
      if (aovs.has(aov::crypto_object) || aovs.has(aov::crypto_material)) {
        if (bad) *bad = item + " (given twice)";
        return std::nullopt;
      }
      aovs.set(aov::crypto_object);
      aovs.set(aov::crypto_material);
      any = true;
      continue;
    }
    const aov_row* found = nullptr;
    for (const aov_row& a : aov_table)
      if (item == a.name) found = &a;
    if (!found || aovs.has(found->id)) {
      if (bad) *bad = found ? item + " (given twice)" : "'" + item + "'";
      return std::nullopt;
    }
    aovs.set(found->id);
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
  for (const aov_row& a : aov_table)
    if (aovs.has(a.id)) out += (out.empty() ? "" : ",") + std::string(a.name);
  return out;
}

bool wants_camera_passes(const aov_set& a) {
  for (const aov_row& row : aov_table)
    if (row.sampling == aov_sampling::filtered && row.shape != aov_shape::rgba &&
        row.shape != aov_shape::per_group && !is_light_split(row.id) && a.has(row.id))
      return true;
  return false;
}

aov_set aov_set_of(std::initializer_list<aov> list) {
  aov_set aovs;
  aovs.bits = 0;
  for (aov a : list) aovs.set(a);
  return aovs;
}

std::optional<depth_mode> parse_depth_mode(const std::string& name) {
  if (name == "distance") return depth_mode::distance;
  if (name == "planar") return depth_mode::planar;
  return std::nullopt;
}

}  // namespace kiln
