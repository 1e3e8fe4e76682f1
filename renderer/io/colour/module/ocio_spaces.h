// The colour module's functions (colour_module.h has their contracts), built into kiln_colour.so
// with OpenColorIO. Internal to the module.
#pragma once

#include "io/colour/colour_module.h"

namespace kiln::colour_module {

void check_config(const colour_config_source& config);

working_space_info working_space(const colour_config_source& config, const std::string& space);

display_transform display_view(const colour_config_source& config, const std::string& space,
                               const std::string& display, const std::string& view);

}  // namespace kiln::colour_module
