#include "job/retired_options.h"

#include <algorithm>

namespace kiln {

const std::vector<retired_option>& retired_options() {
  static const std::vector<retired_option> options = {
      {"texture-cache-mb", "kiln keeps every texture's mip pyramid in memory"},
  };
  return options;
}

const retired_option* find_retired_option(std::string name) {
  name.erase(0, name.find_first_not_of('-'));
  std::replace(name.begin(), name.end(), '_', '-');
  for (const retired_option& option : retired_options())
    if (option.name == name) return &option;
  return nullptr;
}

std::string retired_option_warning(const retired_option& option, const std::string& name) {
  return "warning: " + name + " does nothing (" + option.why + ") and will be removed; drop it";
}

}  // namespace kiln
