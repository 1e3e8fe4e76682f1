#include "io/image_codecs/png_structure.h"

#include <cstring>

namespace kiln {

namespace {

uint32_t read_be32(const uint8_t* p) {
  return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | uint32_t(p[3]);
}

}  // namespace

std::string png_structure_problem(const uint8_t* data, size_t size) {
  size_t pos = 8;  // after the signature
  if (size < pos) return "PNG data is truncated (it ends inside the signature)";
  bool first = true;
  while (true) {
    if (size - pos < 12) return "PNG data is truncated (it ends before the IEND chunk)";
    const uint64_t length = read_be32(data + pos);
    const uint8_t* type = data + pos + 4;
    if (length > 0x7fffffffu) return "PNG chunk length is out of range";
    if (uint64_t(size - pos) < 12 + length)
      return "PNG data is truncated (a chunk runs past the end of the data)";
    if (first && std::memcmp(type, "IHDR", 4) != 0) return "PNG does not start with an IHDR chunk";
    first = false;
    pos += 12 + static_cast<size_t>(length);
    if (std::memcmp(type, "IEND", 4) == 0) return "";
  }
}

}  // namespace kiln
