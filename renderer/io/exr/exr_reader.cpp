#include "io/exr/exr_reader.h"

#include <numeric>

#include "core/error.h"
#include "io/exr/exr_header.h"

namespace kiln {

size_t exr_image::pixel_bytes() const {
  return std::accumulate(channel_bytes.begin(), channel_bytes.end(), size_t(0));
}

exr_image read_exr(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw input_error(path, "", "cannot read EXR: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (in->format_name() != std::string("openexr")) throw input_error(path, "", "not an OpenEXR file");
  if (spec.depth != 1) throw input_error(path, "", "volume images are not supported");
  exr_image image;
  image.data_window = {spec.x, spec.y, spec.x + spec.width, spec.y + spec.height};
  image.display_window = {spec.full_x, spec.full_y, spec.full_x + spec.full_width,
                          spec.full_y + spec.full_height};
  for (int c = 0; c < spec.nchannels; ++c) {
    image.channel_names.push_back(spec.channelnames[size_t(c)]);
    image.channel_formats.push_back(spec.channelformat(c).c_str());
    image.channel_bytes.push_back(spec.channelformat(c).size());
  }
  image.pixels.resize(spec.image_bytes(true));
  // TypeUnknown: every channel in its native format, so nothing is converted.
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeUnknown, image.pixels.data()))
    throw input_error(path, "", "cannot read EXR pixels: " + in->geterror());
  auto header = std::make_shared<exr_header>();
  header->spec = spec;
  image.header = std::move(header);
  return image;
}

std::string exr_string_attribute(const exr_image& image, const std::string& name) {
  if (!image.header) return {};
  return image.header->spec.get_string_attribute(name);
}

}  // namespace kiln
