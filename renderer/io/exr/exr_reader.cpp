#include "io/exr/exr_reader.h"

#include <cstring>
#include <numeric>

#include "core/error.h"
#include "io/exr/exr_header.h"

namespace kiln {

size_t exr_image::pixel_bytes() const {
  return std::accumulate(channel_bytes.begin(), channel_bytes.end(), size_t(0));
}

namespace {

pixel_rect data_window(const OIIO::ImageSpec& spec) {
  return {spec.x, spec.y, spec.x + spec.width, spec.y + spec.height};
}

// Copies one part's interleaved pixels into the image's pixels, whose pixel is `pixel` bytes wide
// and holds this part's channels from byte `offset` on.
void interleave_part(const std::vector<unsigned char>& part, size_t part_pixel,
                     std::vector<unsigned char>& pixels, size_t pixel, size_t offset) {
  const size_t count = part.size() / part_pixel;
  for (size_t i = 0; i < count; ++i)
    std::memcpy(pixels.data() + i * pixel + offset, part.data() + i * part_pixel, part_pixel);
}

}  // namespace

exr_image read_exr(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw input_error(path, "", "cannot read EXR: " + OIIO::geterror());
  if (in->format_name() != std::string("openexr")) throw input_error(path, "", "not an OpenEXR file");
  auto header = std::make_shared<exr_header>();
  // Scanline or tiled, one part or several: OpenImageIO presents each part as a subimage.
  for (int part = 0; in->seek_subimage(part, 0); ++part) header->parts.push_back(in->spec());
  exr_image image;
  const OIIO::ImageSpec& first = header->parts.front();
  image.data_window = data_window(first);
  image.display_window = {first.full_x, first.full_y, first.full_x + first.full_width,
                          first.full_y + first.full_height};
  for (size_t part = 0; part < header->parts.size(); ++part) {
    const OIIO::ImageSpec& spec = header->parts[part];
    const std::string where = "part " + std::to_string(part);
    if (spec.depth != 1) throw input_error(path, where, "volume images are not supported");
    if (!(data_window(spec) == image.data_window))
      throw input_error(path, where, "parts with different data windows are not supported");
    for (int c = 0; c < spec.nchannels; ++c) {
      image.channel_names.push_back(spec.channelnames[size_t(c)]);
      image.channel_formats.push_back(spec.channelformat(c).c_str());
      image.channel_bytes.push_back(spec.channelformat(c).size());
    }
  }
  const size_t pixel = image.pixel_bytes();
  image.pixels.resize(size_t(image.data_window.width()) * size_t(image.data_window.height()) * pixel);
  size_t offset = 0;
  for (size_t part = 0; part < header->parts.size(); ++part) {
    const OIIO::ImageSpec& spec = header->parts[part];
    std::vector<unsigned char> pixels(spec.image_bytes(true));
    // TypeUnknown: every channel in its native format, so nothing is converted.
    if (!in->read_image(int(part), 0, 0, spec.nchannels, OIIO::TypeUnknown, pixels.data()))
      throw input_error(path, "", "cannot read EXR pixels: " + in->geterror());
    interleave_part(pixels, spec.pixel_bytes(true), image.pixels, pixel, offset);
    offset += spec.pixel_bytes(true);
  }
  image.header = std::move(header);
  return image;
}

std::string exr_string_attribute(const exr_image& image, const std::string& name) {
  if (!image.header || image.header->parts.empty()) return {};
  return std::string(image.header->parts.front().get_string_attribute(name));
}

std::optional<float> exr_float_attribute(const exr_image& image, const std::string& name) {
  if (!image.header || image.header->parts.empty()) return std::nullopt;
  const OIIO::ParamValue* value = image.header->parts.front().find_attribute(name, OIIO::TypeFloat);
  if (!value) return std::nullopt;
  return value->get_float();
}

void set_exr_float_attribute(exr_image& image, const std::string& name, float value) {
  auto header = std::make_shared<exr_header>(image.header ? *image.header : exr_header{});
  for (OIIO::ImageSpec& part : header->parts) part.attribute(name, value);
  image.header = std::move(header);
}

void set_exr_string_attribute(exr_image& image, const std::string& name, const std::string& value) {
  auto header = std::make_shared<exr_header>(image.header ? *image.header : exr_header{});
  for (OIIO::ImageSpec& part : header->parts) part.attribute(name, value);
  image.header = std::move(header);
}

}  // namespace kiln
