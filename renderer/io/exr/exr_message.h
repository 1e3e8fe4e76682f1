// OpenEXR's exception messages made fit for kiln's one-line errors. Inside io/exr only.
#pragma once

#include <string>

namespace kiln {

// what as one printable line: without ` "<path>"` (kiln's error names the file already), line
// breaks as spaces and bytes outside printable ASCII (a damaged file's names) as '?'.
std::string exr_message(std::string what, const std::string& path);

}  // namespace kiln
