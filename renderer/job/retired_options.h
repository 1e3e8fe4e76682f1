// Options kiln no longer has but still accepts, so that existing command lines, manifests and
// Python calls keep working: they are not in the option table (no help, no hash, no record), and
// each one given is a one-line warning that it does nothing and will be removed.
#pragma once

#include <string>
#include <vector>

namespace kiln {

struct retired_option {
  std::string name;  // "texture-cache-mb": --texture-cache-mb, texture_cache_mb= in Python
  std::string why;   // why it does nothing, for the warning
};

// Every retired option.
const std::vector<retired_option>& retired_options();

// The retired option named name (with or without the leading dashes, '_' for '-'); nullptr if none.
const retired_option* find_retired_option(std::string name);

// "warning: NAME does nothing (WHY) and will be removed; drop it", NAME as the caller spells it
// (--texture-cache-mb, texture_cache_mb=).
std::string retired_option_warning(const retired_option& option, const std::string& name);

}  // namespace kiln
