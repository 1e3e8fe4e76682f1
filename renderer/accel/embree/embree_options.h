// How the Embree backend builds its BVHs: the build quality (RTC_BUILD_QUALITY_LOW/MEDIUM/HIGH)
// and the compact layout (RTC_SCENE_FLAG_COMPACT). Plain data without Embree's header, so the CLI
// and the reports can name the settings. Images do not depend on them (tests check that).
#pragma once

#include <optional>
#include <string>

namespace kiln {

enum class bvh_quality { low, medium, high };

struct embree_options {
  // Medium is Embree's default and measured best for kiln's renders (docs/performance.md).
  bvh_quality quality = bvh_quality::medium;
  bool compact = false;  // smaller BVH nodes, slower traversal
};

// "low", "medium", "high": the spelling of --bvh-quality.
inline const char* bvh_quality_name(bvh_quality q) {
  return q == bvh_quality::low ? "low" : q == bvh_quality::high ? "high" : "medium";
}

inline std::optional<bvh_quality> parse_bvh_quality(const std::string& name) {
  for (bvh_quality q : {bvh_quality::low, bvh_quality::medium, bvh_quality::high})
    if (name == bvh_quality_name(q)) return q;
  return std::nullopt;
}

}  // namespace kiln
