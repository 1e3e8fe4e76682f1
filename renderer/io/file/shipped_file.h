// Files kiln ships beside its binary (its OpenColorIO config, its studio environment): found in
// ../share/kiln/ beside the running executable once installed, in share/kiln/ of the Python
// package holding the module, else in the source tree's share/.
// Depends on nothing but the standard library.
#pragma once

#include <string>

namespace kiln {

// The path of share/<relative> (e.g. "ocio/kiln.ocio"): the installed copy when there is one.
std::string shipped_file(const std::string& relative);

}  // namespace kiln
