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

void write_preview_image(const std::string& path, int width, int height, int channels,
                         const std::vector<unsigned char>& codes) {
  if (preview_format(path).empty()) throw input_error(path, "", "an image must end in .png, .jpg or .jpeg");
  if (codes.size() != size_t(width) * size_t(height) * size_t(channels))
    throw io_error(
        path, "the image's code values do not fill " + std::to_string(width) + "x" + std::to_string(height));
  load_image_codecs("writing an image needs")
      .write_preview_image(path, width, height, channels, codes.data());
}

bool preview_complete(const std::string& preview_path, int width, int height) {
  if (preview_format(preview_path).empty()) return false;
  return load_image_codecs("checking a preview needs").preview_complete(preview_path, width, height);
}

}  // namespace kiln
