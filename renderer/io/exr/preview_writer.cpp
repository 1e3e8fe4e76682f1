#include "io/exr/preview_writer.h"

#include "core/error.h"
#include "io/image_codecs/codecs_loader.h"

namespace kiln {

void write_preview(const std::string& exr_path, const std::string& preview_path, double exposure,
                   const display_transform* view) {
  // A bad name is refused before the module is looked for.
  if (preview_format(preview_path).empty())
    throw input_error(preview_path, "--preview", "a preview must end in .png, .jpg or .jpeg");
  load_image_codecs("a preview needs").write_preview(exr_path, preview_path, exposure, view);
}

bool preview_complete(const std::string& preview_path, int width, int height) {
  if (preview_format(preview_path).empty()) return false;
  return load_image_codecs("checking a preview needs").preview_complete(preview_path, width, height);
}

}  // namespace kiln
