// Finds and opens the colour module (kiln_colour.so) the first time a render names a working
// space or an OpenColorIO config, and finds the config to use. A render that does neither never
// maps OpenColorIO. Depends on core, the plugin loader and the module's table only.
#pragma once

#include <string>

#include "io/colour/colour_module.h"

namespace kiln {

// The file name of the module, the same in the build tree and after install.
constexpr const char* colour_module_file_name = "kiln_colour.so";

// The module's table, opened once (thread-safe) on the first call. Throws kiln::error (io) with
// one line when the module cannot be found or opened: "<needs> the colour module: <path>: <why>".
const colour_functions& load_colour_module(const std::string& needs);

// The config a render uses: config_option (--ocio-config) when given, else $OCIO when set, else
// kiln's own (share/ocio/kiln.ocio: ../share/kiln/ocio/ beside the executable once installed, the
// source tree's otherwise).
colour_config_source find_colour_config(const std::string& config_option);

// Whether find_colour_config would use a config the user chose (--ocio-config or $OCIO).
bool user_colour_config(const std::string& config_option);

// kiln's own config: the first of the places above that exists, else the source tree's path.
std::string shipped_colour_config();

}  // namespace kiln
