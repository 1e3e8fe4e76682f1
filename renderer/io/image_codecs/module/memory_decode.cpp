// Decodes an encoded glTF image (PNG, JPEG, ...) from memory with OpenImageIO. The caller
// silences stderr around a batch of decodes: libpng prints its own messages there.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "io/image_codecs/module/codecs_module.h"
#include "io/image_codecs/png_structure.h"

namespace kiln::codecs_module {
namespace {

// Encoded bytes owned by the caller.
struct byte_span {
  const uint8_t* bytes = nullptr;
  size_t length = 0;
  size_t size() const { return length; }
  const uint8_t* data() const { return bytes; }
  uint8_t operator[](size_t i) const { return bytes[i]; }
};

bool starts_with(const byte_span& bytes, const char* magic, size_t offset = 0) {
  const size_t n = std::strlen(magic);
  return bytes.size() >= offset + n && std::memcmp(bytes.data() + offset, magic, n) == 0;
}

// OpenImageIO picks a reader from the file name's extension; in-memory data has no name, so
// derive one from the magic bytes. Empty when the format is not one kiln expects in glTF.
std::string name_from_magic(const byte_span& bytes) {
  if (starts_with(bytes, "\x89PNG\r\n\x1a\n")) return "image.png";
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return "image.jpg";
  if (starts_with(bytes, "RIFF") && starts_with(bytes, "WEBP", 8)) return "image.webp";
  if (starts_with(bytes, "GIF87a") || starts_with(bytes, "GIF89a")) return "image.gif";
  if (starts_with(bytes, "BM")) return "image.bmp";
  return "";
}

// Expands n source channels (grey, grey+alpha, RGB, RGBA, or more) to RGBA.
template <typename T>
void expand_to_rgba(const std::vector<T>& src, int channels, size_t texels, T opaque, std::vector<T>& dst) {
  dst.resize(texels * 4);
  for (size_t i = 0; i < texels; ++i) {
    const T* s = src.data() + i * static_cast<size_t>(channels);
    T* d = dst.data() + i * 4;
    if (channels == 1) {
      d[0] = d[1] = d[2] = s[0];
      d[3] = opaque;
    } else if (channels == 2) {
      d[0] = d[1] = d[2] = s[0];
      d[3] = s[1];
    } else {
      d[0] = s[0];
      d[1] = s[1];
      d[2] = s[2];
      d[3] = channels >= 4 ? s[3] : opaque;
    }
  }
}

// OpenImageIO's messages may span lines; kiln's error is one line.
std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (size_t pos; (pos = text.find('\n')) != std::string::npos;) text.replace(pos, 1, "; ");
  return text;
}

// OpenImageIO names the file it read in its messages; for in-memory data that is the made-up
// name from name_from_magic, which would only mislead.
std::string without_name(std::string text, const std::string& pseudo_name) {
  const std::string quoted_name = " (\"" + pseudo_name + "\")";
  for (size_t pos; (pos = text.find(quoted_name)) != std::string::npos;) text.erase(pos, quoted_name.size());
  return text;
}

}  // namespace

image decode(const uint8_t* data, size_t size, const std::string& name, const std::string& file,
             const std::string& where, uint64_t max_texels) {
  const byte_span encoded{data, size};
  auto fail = [&](const std::string& reason) { return input_error(file, where, reason); };
  const std::string pseudo_name = name_from_magic(encoded);
  if (pseudo_name.empty()) throw fail("image data is not PNG, JPEG, WebP, GIF or BMP");
  if (pseudo_name == "image.png") {
    // A truncated PNG must be refused before libpng sees it: libpng reports a short read by
    // longjmp-ing out of OpenImageIO's read callback, past C++ destructors, which leaks memory.
    const std::string problem = png_structure_problem(encoded.data(), encoded.size());
    if (!problem.empty()) throw fail("cannot decode image: " + problem);
  }

  OIIO::Filesystem::IOMemReader proxy(encoded.data(), encoded.size());
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // glTF alpha is straight, not premultiplied
  // OIIO 2.4's readers take the proxy from this hint: the ioproxy argument of open() alone is
  // overridden when the reader re-reads its configuration. The attribute stores the pointer's value.
  OIIO::Filesystem::IOProxy* proxy_pointer = &proxy;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy_pointer);
  auto input = OIIO::ImageInput::open(pseudo_name, &config, &proxy);
  if (!input) {
    std::string why = without_name(one_line(OIIO::geterror()), pseudo_name);
    throw fail("cannot decode image: " + (why.empty() ? std::string("unknown error") : why));
  }
  const OIIO::ImageSpec& spec = input->spec();
  const int channels = spec.nchannels;
  if (spec.width <= 0 || spec.height <= 0 || channels <= 0 || spec.depth > 1)
    throw fail("image has invalid dimensions");
  const uint64_t texels = static_cast<uint64_t>(spec.width) * static_cast<uint64_t>(spec.height);
  if (texels > max_texels)
    throw fail("image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
               " texels, over the limit of " + std::to_string(max_texels) + " (--max-texels)");

  image out;
  out.name = name;
  out.width = spec.width;
  out.height = spec.height;
  const int used_channels = std::min(channels, 4);
  const bool eight_bit = spec.format == OIIO::TypeDesc::UINT8;
  // OpenImageIO returns scanlines top to bottom, which is glTF's UV origin: no flip.
  bool ok = false;
  if (eight_bit) {
    std::vector<uint8_t> pixels(texels * static_cast<size_t>(used_channels));
    ok = input->read_image(0, 0, 0, used_channels, OIIO::TypeDesc::UINT8, pixels.data());
    if (ok) expand_to_rgba<uint8_t>(pixels, used_channels, texels, 255, out.texels8);
  } else {
    std::vector<float> pixels(texels * static_cast<size_t>(used_channels));
    ok = input->read_image(0, 0, 0, used_channels, OIIO::TypeDesc::FLOAT, pixels.data());
    if (ok) expand_to_rgba<float>(pixels, used_channels, texels, 1.0f, out.texels32);
  }
  // libjpeg only warns about a truncated or corrupt stream ("Premature end of JPEG file") and fills
  // the rest with grey; OpenImageIO records the warning yet reports success. Such an image is as
  // broken as a truncated PNG, so the warning refuses it. (Other readers may record harmless
  // warnings, such as libpng's about colour profiles, so only JPEG's count.)
  std::string why = without_name(one_line(input->geterror()), pseudo_name);
  if (!ok || (pseudo_name == "image.jpg" && !why.empty()))
    throw fail("cannot decode image: " + (why.empty() ? std::string("truncated or corrupt data") : why));
  return out;
}

}  // namespace kiln::codecs_module
