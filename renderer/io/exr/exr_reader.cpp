#include "io/exr/exr_reader.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfTestFile.h>

#include <algorithm>
#include <exception>
#include <limits>
#include <numeric>

#include "core/error.h"
#include "core/memory_budget.h"
#include "io/exr/exr_base_header.h"
#include "io/exr/exr_header.h"
#include "io/exr/exr_header_copy.h"
#include "io/exr/exr_message.h"
#include "io/exr/exr_threads.h"

namespace kiln {

size_t exr_image::pixel_bytes() const {
  return std::accumulate(channel_bytes.begin(), channel_bytes.end(), size_t(0));
}

namespace {

pixel_rect rect_of(const Imath::Box2i& box) { return {box.min.x, box.min.y, box.max.x + 1, box.max.y + 1}; }

// OpenImageIO's names for the formats, which exr_image has always used.
const char* format_name(Imf::PixelType type) {
  switch (type) {
    case Imf::UINT:
      return "uint";
    case Imf::HALF:
      return "half";
    case Imf::FLOAT:
      return "float";
    default:
      return "";
  }
}

size_t format_bytes(Imf::PixelType type) { return type == Imf::HALF ? 2 : 4; }

// Checks the parts' layout and lists their channels into image (names, formats, sizes).
void describe_parts(const std::string& path, const exr_header& header, exr_image& image) {
  const Imf::Header& first = header.parts.front();
  image.data_window = rect_of(first.dataWindow());
  image.display_window = rect_of(first.displayWindow());
  for (size_t part = 0; part < header.parts.size(); ++part) {
    const Imf::Header& h = header.parts[part];
    const std::string where = "part " + std::to_string(part);
    if (h.hasType() && Imf::isDeepData(h.type()))
      throw input_error(path, where, "deep images are not supported");
    if (!(rect_of(h.dataWindow()) == image.data_window))
      throw input_error(path, where, "parts with different data windows are not supported");
    for (auto c = h.channels().begin(); c != h.channels().end(); ++c) {
      if (c.channel().xSampling != 1 || c.channel().ySampling != 1)
        throw input_error(path, where,
                          std::string("channel ") + c.name() + " is subsampled, which is not supported");
      if (*format_name(c.channel().type) == '\0')
        throw input_error(path, where, std::string("channel ") + c.name() + " has an unknown sample format");
      image.channel_names.push_back(c.name());
      image.channel_formats.push_back(format_name(c.channel().type));
      image.channel_bytes.push_back(format_bytes(c.channel().type));
    }
  }
}

}  // namespace

exr_image read_exr(const std::string& path, memory_budget* budget) {
  bool tiled = false, deep = false, multipart = false;
  if (!Imf::isOpenExrFile(path.c_str(), tiled, deep, multipart)) {
    std::FILE* probe = std::fopen(path.c_str(), "rbe");
    if (!probe) throw input_error(path, "", "cannot read EXR: cannot open the file");
    std::fclose(probe);
    throw input_error(path, "", "not an OpenEXR file");
  }
  use_exr_threads();
  exr_image image;
  auto header = std::make_shared<exr_header>();
  try {
    // Scanline or tiled, one part or several: a single-part file reads as a file of one part.
    Imf::MultiPartInputFile file(path.c_str());
    for (int part = 0; part < file.parts(); ++part) header->parts.push_back(file.header(part));
    if (header->parts.empty()) throw input_error(path, "", "the file has no parts");
    describe_parts(path, *header, image);
    const pixel_rect& d = image.data_window;
    const size_t pixel = image.pixel_bytes();
    const uint64_t count = uint64_t(d.width()) * uint64_t(d.height());
    if (d.width() <= 0 || d.height() <= 0 || pixel == 0 || count > std::numeric_limits<size_t>::max() / pixel)
      throw input_error(path, "dataWindow", "no pixels to read, or too many");
    if (budget) budget->charge(count * pixel, path, "the data window's pixels");
    image.pixels.resize(size_t(count) * pixel);
    // Every part's channels land in their own place of each interleaved pixel, in the file's
    // formats: nothing is converted. Reading every pixel is what finds a truncated file.
    size_t offset = 0;
    const Imath::Box2i& window = header->parts.front().dataWindow();
    for (int part = 0; part < file.parts(); ++part) {
      Imf::FrameBuffer buffer;
      for (auto c = header->parts[size_t(part)].channels().begin();
           c != header->parts[size_t(part)].channels().end(); ++c) {
        buffer.insert(c.name(),
                      Imf::Slice::Make(c.channel().type, image.pixels.data() + offset, window, pixel));
        offset += format_bytes(c.channel().type);
      }
      Imf::InputPart in(file, part);
      in.setFrameBuffer(buffer);
      in.readPixels(window.min.y, window.max.y);
    }
  } catch (const error&) {
    throw;
  } catch (const std::exception& e) {  // Iex::BaseExc for a damaged file, std::bad_alloc for a huge one
    throw input_error(path, "", "cannot read EXR: " + exr_message(e.what(), path));
  }
  image.header = std::move(header);
  return image;
}

std::string exr_string_attribute(const exr_image& image, const std::string& name) {
  if (!image.header || image.header->parts.empty()) return {};
  const auto* value = image.header->parts.front().findTypedAttribute<Imf::StringAttribute>(name);
  return value ? value->value() : std::string();
}

std::optional<float> exr_float_attribute(const exr_image& image, const std::string& name) {
  if (!image.header || image.header->parts.empty()) return std::nullopt;
  const auto* value = image.header->parts.front().findTypedAttribute<Imf::FloatAttribute>(name);
  if (!value) return std::nullopt;
  return value->value();
}

void set_exr_attribute(exr_image& image, const std::string& name, const exr_value& value) {
  auto header = std::make_shared<exr_header>(image.header ? *image.header : exr_header{});
  for (Imf::Header& part : header->parts) insert_exr_attribute(part, name, value);
  image.header = std::move(header);
}

}  // namespace kiln
