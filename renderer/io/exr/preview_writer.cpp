#include "io/exr/preview_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "io/exr/atomic_write.h"
#include "io/exr/exr_beauty.h"
#include "io/exr/preview_record.h"
#include "io/image_codecs/direct_decode.h"
#include "io/image_codecs/direct_encode.h"

namespace kiln {

namespace {

// The preview's 8-bit codes of an EXR's beauty (channels 4: R G B and straight A; 3: R G B over
// black), through the display transform view when there is one, else preview_code.
std::vector<unsigned char> preview_codes(const rgba_image& beauty, int channels, double exposure,
                                         const display_transform* view) {
  const std::vector<float>& rgba = beauty.pixels;
  const size_t pixel_count = size_t(beauty.width) * size_t(beauty.height);
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
    const preview_code_table table = make_preview_code_table(exposure);
    for (size_t i = 0; i < pixel_count; ++i) {
      const float straight = unpremultiply(i);
      for (size_t c = 0; c < 3; ++c)
        codes[i * size_t(channels) + c] = preview_code(table, rgba[i * 4 + c] * straight);
    }
  }
  if (channels == 4)
    for (size_t i = 0; i < pixel_count; ++i) codes[i * 4 + 3] = (unsigned char)std::lround(255.0f * alpha(i));
  return codes;
}

// The file's last bytes, which every complete file of the format ends with: a truncated JPEG
// otherwise decodes as grey.
bool ends_with_trailer(const std::vector<unsigned char>& bytes, const std::string& format) {
  static const unsigned char png_end[] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  static const unsigned char jpeg_end[] = {0xFF, 0xD9};
  const unsigned char* end = format == "png" ? png_end : jpeg_end;
  const size_t n = format == "png" ? sizeof png_end : sizeof jpeg_end;
  return bytes.size() >= n && std::memcmp(bytes.data() + bytes.size() - n, end, n) == 0;
}

bool starts_as(const std::vector<unsigned char>& bytes, const std::string& format) {
  static const unsigned char png_start[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  static const unsigned char jpeg_start[] = {0xFF, 0xD8, 0xFF};
  const unsigned char* start = format == "png" ? png_start : jpeg_start;
  const size_t n = format == "png" ? sizeof png_start : sizeof jpeg_start;
  return bytes.size() >= n && std::memcmp(bytes.data(), start, n) == 0;
}

}  // namespace

void write_preview(const std::string& exr_path, const std::string& preview_path, double exposure,
                   const display_transform* view, const std::atomic<bool>* cancel) {
  if (preview_format(preview_path).empty())
    throw input_error(preview_path, "--preview", "a preview must end in .png, .jpg or .jpeg");
  const std::optional<rgba_image> beauty = read_exr_beauty(exr_path);
  if (!beauty) throw input_error(exr_path, "--preview", "the EXR holds no R G B A to preview");
  write_preview(*beauty, preview_path, exposure, view, cancel);
}

void write_preview(const rgba_image& beauty, const std::string& preview_path, double exposure,
                   const display_transform* view, const std::atomic<bool>* cancel) {
  const int channels = preview_format(preview_path) == "png" ? 4 : 3;
  write_preview_image(preview_path, beauty.width, beauty.height, channels,
                      preview_codes(beauty, channels, exposure, view), cancel);
}

void write_preview_image(const std::string& path, int width, int height, int channels,
                         const std::vector<unsigned char>& codes, const std::atomic<bool>* cancel) {
  const std::string format = preview_format(path);
  if (format.empty()) throw input_error(path, "", "an image must end in .png, .jpg or .jpeg");
  if (width <= 0 || height <= 0 || (channels != 3 && channels != 4))
    throw io_error(path, "cannot encode a " + std::to_string(width) + "x" + std::to_string(height) +
                             " image of " + std::to_string(channels) + " channels");
  if (codes.size() != size_t(width) * size_t(height) * size_t(channels))
    throw io_error(
        path, "the image's code values do not fill " + std::to_string(width) + "x" + std::to_string(height));
  std::vector<unsigned char> encoded;
  std::string problem;
  if (format == "png") {
    problem = encode_png(width, height, channels, codes.data(), encoded);
  } else if (channels == 3) {
    problem = encode_jpeg(width, height, codes.data(), encoded);
  } else {  // JPEG has no alpha: the fourth channel is dropped
    std::vector<unsigned char> rgb(size_t(width) * size_t(height) * 3);
    for (size_t i = 0; i < rgb.size() / 3; ++i) std::copy_n(&codes[i * 4], 3, &rgb[i * 3]);
    problem = encode_jpeg(width, height, rgb.data(), encoded);
  }
  if (!problem.empty()) throw io_error(path, "cannot encode " + format + ": " + problem);
  encoded = with_checksum_record(encoded, format);
  // The error names the format as earlier kilns did ("cannot write png: ...").
  write_atomically(
      path, format,
      [&](const temporary_file& temporary) {
        return write_all(temporary.fd, encoded.data(), encoded.size());
      },
      cancel);
}

bool preview_complete(const std::string& preview_path, int width, int height) {
  const std::string format = preview_format(preview_path);
  if (format.empty()) return false;
  std::ifstream in(preview_path, std::ios::binary);
  if (!in) return false;
  // A read cut short leaves the file without its trailer.
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  if (!starts_as(bytes, format) || !ends_with_trailer(bytes, format)) return false;
  // Decoded by libpng or libjpeg, which refuse (as a failed decode) any error or warning on the way.
  const std::optional<image> decoded =
      decode_directly(bytes.data(), bytes.size(), uint64_t(width) * uint64_t(height));
  return decoded && decoded->width == width && decoded->height == height;
}

}  // namespace kiln
