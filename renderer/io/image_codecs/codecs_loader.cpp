#include "io/image_codecs/codecs_loader.h"

#include "core/error.h"
#include "io/plugin/plugin_module.h"

namespace kiln {

namespace {

// KILN_IMAGE_CODECS_BUILD_PATH (from CMake): the build tree's copy, for tests and tools built in
// other folders.
plugin_search codecs_search() {
  return {image_codecs_file_name,  "KILN_IMAGE_CODECS", KILN_IMAGE_CODECS_BUILD_PATH,
          KILN_IMAGE_CODECS_ENTRY, image_codecs_abi,    sizeof(image_codecs)};
}

}  // namespace

std::vector<std::string> image_codecs_candidates() { return plugin_candidates(codecs_search()); }

const image_codecs& load_image_codecs(const std::string& needs) {
  return plugin_table<image_codecs>(codecs_search(), needs, "image codecs module");
}

}  // namespace kiln
