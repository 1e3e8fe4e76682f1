// Finds and opens the image codecs module (kiln_image_codecs.so) the first time kiln needs to read
// an image it does not decode itself, so a render without such images never maps OpenImageIO and
// its ~260 libraries. Depends on core and the module's table only.
#pragma once

#include <string>
#include <vector>

#include "io/image_codecs/image_codecs.h"

namespace kiln {

// The file name of the module, the same in the build tree and after install.
constexpr const char* image_codecs_file_name = "kiln_image_codecs.so";

// Where the module is looked for, in order: $KILN_IMAGE_CODECS alone when set; else beside the
// running executable, in ../lib/kiln/ beside it (an install), and the build tree's copy.
std::vector<std::string> image_codecs_candidates();

// The module's table, opened once (thread-safe) on the first call. Throws kiln::error (io) with one
// line when the module cannot be found or opened: "<needs> the image codecs module: <path>: <why>",
// where needs says what asked for it (e.g. "textures need").
const image_codecs& load_image_codecs(const std::string& needs);

}  // namespace kiln
