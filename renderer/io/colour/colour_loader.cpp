#include "io/colour/colour_loader.h"

#include <cstdlib>

#include "core/error.h"
#include "io/file/shipped_file.h"
#include "io/plugin/plugin_module.h"

namespace kiln {

namespace {

// KILN_COLOUR_BUILD_PATH (from CMake): the build tree's copy, for tests built in other folders.
plugin_search colour_search() {
  return {colour_module_file_name, "KILN_COLOUR_MODULE", KILN_COLOUR_BUILD_PATH,
          KILN_COLOUR_ENTRY,       colour_module_abi,    sizeof(colour_functions)};
}

const char* ocio_variable() {
  const char* value = std::getenv("OCIO");
  return value && *value ? value : nullptr;
}

}  // namespace

const colour_functions& load_colour_module(const std::string& needs) {
  return plugin_table<colour_functions>(colour_search(), needs, "colour module");
}

bool user_colour_config(const std::string& config_option) {
  return !config_option.empty() || ocio_variable();
}

colour_config_source find_colour_config(const std::string& config_option) {
  if (!config_option.empty()) return {config_option, "--ocio-config"};
  if (const char* variable = ocio_variable()) return {variable, "$OCIO"};
  return {shipped_colour_config(), "kiln's own config"};
}

std::string shipped_colour_config() { return shipped_file("ocio/kiln.ocio"); }

}  // namespace kiln
