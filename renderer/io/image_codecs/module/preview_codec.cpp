// Writes the 8-bit PNG or JPEG preview of an EXR's beauty and checks a written one, with
// OpenImageIO (which also reads the EXR here, so the module needs nothing from kiln's EXR code).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

#include "core/error.h"
#include "io/exr/atomic_write.h"
#include "io/exr/preview_codes.h"
#include "io/image_codecs/module/codecs_module.h"

namespace kiln::codecs_module {
namespace {

// Moves in to the subimage (part) that holds R, G, B and A and sets first_channel to the index of
// R in it (OpenImageIO orders them R, G, B, A); false when none does.
bool seek_beauty(OIIO::ImageInput& in, int& first_channel) {
  for (int part = 0; in.seek_subimage(part, 0); ++part) {
    const OIIO::ImageSpec& spec = in.spec();
    const int r = spec.channelindex("R");
    if (r >= 0 && r + 3 < spec.nchannels && spec.channelnames[size_t(r) + 1] == "G" &&
        spec.channelnames[size_t(r) + 2] == "B" && spec.channelnames[size_t(r) + 3] == "A") {
      first_channel = r;
      return true;
    }
  }
  return false;
}

// The last bytes every complete file of the format ends with.
bool ends_with_trailer(const std::string& path, const std::string& format) {
  static const unsigned char png_end[] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  static const unsigned char jpeg_end[] = {0xFF, 0xD9};
  const std::string trailer = format == "png" ? std::string(png_end, png_end + sizeof png_end)
                                              : std::string(jpeg_end, jpeg_end + sizeof jpeg_end);
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in || in.tellg() < std::streamoff(trailer.size())) return false;
  in.seekg(-std::streamoff(trailer.size()), std::ios::end);
  std::string tail(trailer.size(), '\0');
  return bool(in.read(tail.data(), std::streamsize(tail.size()))) && tail == trailer;
}

// The whole file in memory; throws kiln::error (io) when OpenImageIO cannot encode it.
std::vector<unsigned char> encode(const std::string& format, const OIIO::ImageSpec& spec,
                                  const std::vector<unsigned char>& codes) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto out = OIIO::ImageOutput::create(format);
  if (!out) throw io_error("", "OpenImageIO has no " + format + " writer: " + OIIO::geterror());
  bool ok = out->set_ioproxy(&memory) && out->open("preview." + format, spec) &&
            out->write_image(OIIO::TypeDesc::UINT8, codes.data());
  ok = out->close() && ok;
  if (!ok) throw io_error("", "cannot encode " + format + ": " + out->geterror());
  return bytes;
}

// Encodes 8-bit sRGB codes (straight alpha when the spec has it) and writes them to path atomically.
void write_encoded(const std::string& path, const std::string& format, OIIO::ImageSpec spec,
                   const std::vector<unsigned char>& codes) {
  spec.attribute("oiio:ColorSpace", "sRGB");
  if (format == "jpeg") spec.attribute("Compression", "jpeg:95");
  // Encoded in memory, then written with every write checked: OpenImageIO's PNG writer does not
  // report a write that fails (a full disk), which would rename a truncated file into place.
  const std::vector<unsigned char> encoded = encode(format, spec, codes);
  // The error names the format as earlier kilns did ("cannot write png: ...").
  write_atomically(path, format, [&](const temporary_file& temporary) {
    return write_all(temporary.fd, encoded.data(), encoded.size());
  });
}

}  // namespace

bool preview_complete(const std::string& preview_path, int width, int height) {
  const std::string format = preview_format(preview_path);
  if (format.empty() || !ends_with_trailer(preview_path, format)) return false;
  auto in = OIIO::ImageInput::open(preview_path);
  if (!in) {
    OIIO::geterror();  // clear the message OpenImageIO keeps for the thread
    return false;
  }
  const OIIO::ImageSpec spec = in->spec();
  if (in->format_name() != format || spec.width != width || spec.height != height) return false;
  std::vector<unsigned char> pixels(spec.image_bytes());
  const bool read = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data());
  if (!read) in->geterror();
  return read;
}

void write_preview(const std::string& exr_path, const std::string& preview_path, double exposure,
                   const display_transform* view) {
  const std::string format = preview_format(preview_path);
  if (format.empty())
    throw input_error(preview_path, "--preview", "a preview must end in .png, .jpg or .jpeg");
  auto in = OIIO::ImageInput::open(exr_path);
  if (!in) throw input_error(exr_path, "", "cannot read EXR: " + OIIO::geterror());
  int r = 0;
  if (!seek_beauty(*in, r)) throw input_error(exr_path, "--preview", "the EXR holds no R G B A to preview");
  const OIIO::ImageSpec spec = in->spec();
  const size_t pixel_count = size_t(spec.width) * size_t(spec.height);
  std::vector<float> rgba(pixel_count * 4);
  if (!in->read_image(in->current_subimage(), 0, r, r + 4, OIIO::TypeDesc::FLOAT, rgba.data()))
    throw input_error(exr_path, "", "cannot read EXR pixels: " + in->geterror());

  const int channels = format == "png" ? 4 : 3;
  std::vector<unsigned char> codes(pixel_count * size_t(channels));
  const auto alpha = [&](size_t i) {
    return std::isnan(rgba[i * 4 + 3]) ? 0.0f : std::clamp(rgba[i * 4 + 3], 0.0f, 1.0f);
  };
  // PNG stores straight alpha, so its colour is unpremultiplied and a viewer's "over" is right;
  // JPEG has no alpha and shows the premultiplied colour, i.e. the image over black.
  const auto unpremultiply = [&](size_t i) {
    return channels == 4 && alpha(i) > 0.0f ? 1.0f / alpha(i) : 1.0f;
  };
  if (view && *view) {
    // An OpenColorIO display/view: exposure on the scene-linear colour, then the view, whose
    // display code values [0, 1] are quantised as the sRGB curve's are.
    std::vector<float> rgb(pixel_count * 3);
    const float scale = float(std::exp2(exposure));
    for (size_t i = 0; i < pixel_count; ++i)
      for (size_t c = 0; c < 3; ++c) rgb[i * 3 + c] = rgba[i * 4 + c] * unpremultiply(i) * scale;
    (*view)(rgb.data(), pixel_count);
    for (size_t i = 0; i < pixel_count; ++i)
      for (size_t c = 0; c < 3; ++c) {
        const float v = rgb[i * 3 + c];
        codes[i * size_t(channels) + c] =
            std::isnan(v) ? 0 : (unsigned char)std::lround(255.0f * std::clamp(v, 0.0f, 1.0f));
      }
  } else {
    for (size_t i = 0; i < pixel_count; ++i)
      for (size_t c = 0; c < 3; ++c)
        codes[i * size_t(channels) + c] = preview_code(rgba[i * 4 + c] * unpremultiply(i), exposure);
  }
  if (channels == 4)
    for (size_t i = 0; i < pixel_count; ++i) codes[i * 4 + 3] = (unsigned char)std::lround(255.0f * alpha(i));
  OIIO::ImageSpec out_spec(spec.width, spec.height, channels, OIIO::TypeDesc::UINT8);
  if (channels == 4) {
    out_spec.alpha_channel = 3;
    // The codes are already straight: without this OpenImageIO would divide colour by alpha again.
    out_spec.attribute("oiio:UnassociatedAlpha", 1);
  }
  write_encoded(preview_path, format, out_spec, codes);
}

void write_preview_image(const std::string& path, int width, int height, int channels,
                         const unsigned char* codes) {
  const std::string format = preview_format(path);
  if (format.empty()) throw input_error(path, "", "an image must end in .png, .jpg or .jpeg");
  if (width <= 0 || height <= 0 || (channels != 3 && channels != 4))
    throw io_error(path, "cannot encode a " + std::to_string(width) + "x" + std::to_string(height) +
                             " image of " + std::to_string(channels) + " channels");
  // JPEG has no alpha: a fourth channel is dropped.
  const int stored = format == "jpeg" ? 3 : channels;
  const size_t pixels = size_t(width) * size_t(height);
  std::vector<unsigned char> kept(pixels * size_t(stored));
  for (size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < stored; ++c)
      kept[i * size_t(stored) + size_t(c)] = codes[i * size_t(channels) + size_t(c)];
  OIIO::ImageSpec spec(width, height, stored, OIIO::TypeDesc::UINT8);
  if (stored == 4) {
    spec.alpha_channel = 3;
    spec.attribute("oiio:UnassociatedAlpha", 1);
  }
  write_encoded(path, format, spec, kept);
}

}  // namespace kiln::codecs_module
