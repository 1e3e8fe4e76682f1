// Ray counts of the stability suite: full in a plain build, fewer under a sanitizer (the CI runs
// the suite under ASan+UBSan, which is ~10× slower), so the whole suite stays within minutes.
#pragma once

namespace kiln::testing {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_UNDEFINED__)
constexpr bool sanitized_build = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
constexpr bool sanitized_build = true;
#else
constexpr bool sanitized_build = false;
#endif
#else
constexpr bool sanitized_build = false;
#endif

// Full count in a plain build, a quarter under a sanitizer.
constexpr int ray_budget(int full) { return sanitized_build ? full / 4 : full; }

}  // namespace kiln::testing
