#include "render/aov_list.h"

#include <sstream>

#include "render/aov_table.h"

namespace kiln {

namespace {

// Shorthand for both Cryptomatte layers.
constexpr const char* cryptomatte_name = "cryptomatte";

}  // namespace

std::optional<aov_set> parse_aov_list(const std::string& text, std::string* bad) {
  aov_set aovs;
  for (const aov_row& a : aov_table) aovs.*a.flag = false;
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
    const aov_row* found = nullptr;
    for (const aov_row& a : aov_table)
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
  for (const aov_row& a : aov_table)
    if (aovs.*a.flag) out += (out.empty() ? "" : ",") + std::string(a.name);
  return out;
}

std::optional<depth_mode> parse_depth_mode(const std::string& name) {
  if (name == "distance") return depth_mode::distance;
  if (name == "planar") return depth_mode::planar;
  return std::nullopt;
}

}  // namespace kiln
