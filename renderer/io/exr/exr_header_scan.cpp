#include "io/exr/exr_header_scan.h"

#include <OpenEXR/openexr.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>

namespace kiln {

int64_t exr_lines_per_chunk(int compression) {
  switch (compression) {
    case 3:  // ZIP
    case 5:  // PXR24
      return 16;
    case 4:  // PIZ
    case 6:  // B44
    case 7:  // B44A
    case 8:  // DWAA
      return 32;
    case 9:  // DWAB
      return 256;
    default:  // none, RLE, ZIPS
      return 1;
  }
}

namespace {

struct part_facts {
  int64_t width = 0, height = 0;
  int compression = 0;
  int64_t tile_x = 0, tile_y = 0;
  bool deep = false;
};

// The least number of chunks a part's offset table lists (tiled files: the first level's tiles).
int64_t chunk_count(const part_facts& p) {
  if (p.width <= 0 || p.height <= 0) return 0;
  if (p.tile_x > 0 && p.tile_y > 0)
    return ((p.width + p.tile_x - 1) / p.tile_x) * ((p.height + p.tile_y - 1) / p.tile_y);
  return (p.height + exr_lines_per_chunk(p.compression) - 1) / exr_lines_per_chunk(p.compression);
}

}  // namespace

namespace {

// OpenEXR's own reader of the C++ library reads some attributes by their contents, not by their
// declared size, so a header the scan below passes may still be read another way; OpenEXRCore's
// strict parse (which checks every size against the file) must accept it too.
std::string core_parse_problem(const std::string& path) {
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.flags = EXR_CONTEXT_FLAG_STRICT_HEADER | EXR_CONTEXT_FLAG_SILENT_HEADER_PARSE |
               EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
  init.error_handler_fn = [](exr_const_context_t, exr_result_t, const char*) {};
  exr_context_t context = nullptr;
  const exr_result_t result = exr_start_read(&context, path.c_str(), &init);
  if (context) exr_finish(&context);
  if (result == EXR_ERR_SUCCESS) return "";
  return std::string("its header does not parse (") + exr_get_default_error_message(result) + ")";
}

}  // namespace

std::string exr_header_sizes_problem(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return "cannot be opened";
  const int64_t size = int64_t(in.tellg());
  in.seekg(0);
  unsigned char start[8];
  if (!in.read(reinterpret_cast<char*>(start), 8)) return "shorter than an EXR's first bytes";
  const bool multipart = (start[5] & 0x10) != 0;  // the version field's flags, bit 12
  const auto read_name = [&in](std::string& name) {
    name.clear();
    for (char c; in.get(c);) {
      if (c == '\0') return true;
      if (name.size() == 255) return false;
      name += c;
    }
    return false;
  };
  int64_t tables = 0;  // bytes the parts' offset tables take
  for (int part = 0;; ++part) {
    part_facts facts;
    std::string name, type;
    int attributes = 0;
    while (true) {
      if (!read_name(name)) return "a header attribute's name is cut short or too long";
      if (name.empty()) break;
      if (!read_name(type)) return "the type of header attribute " + name + " is cut short or too long";
      int32_t declared = 0;
      if (!in.read(reinterpret_cast<char*>(&declared), 4))
        return "header attribute " + name + " is cut short";
      const int64_t at = int64_t(in.tellg());
      if (declared < 0 || declared > size - at)
        return "header attribute " + name + " declares " + std::to_string(declared) +
               " bytes, more than the " + std::to_string(size - at) + " left in the file";
      unsigned char value[16] = {};
      const int64_t keep = std::min<int64_t>(declared, sizeof value);
      in.read(reinterpret_cast<char*>(value), keep);
      in.seekg(at + declared);
      int32_t v[4];
      std::memcpy(v, value, sizeof v);
      if (name == "dataWindow" && type == "box2i" && declared == 16) {
        facts.width = int64_t(v[2]) - v[0] + 1;
        facts.height = int64_t(v[3]) - v[1] + 1;
      } else if (name == "compression" && declared == 1) {
        facts.compression = value[0];
      } else if (name == "tiles" && type == "tiledesc" && declared >= 8) {
        facts.tile_x = uint32_t(v[0]);
        facts.tile_y = uint32_t(v[1]);
      } else if (name == "type" && type == "string") {
        facts.deep = std::string(reinterpret_cast<char*>(value), size_t(keep)).rfind("deep", 0) == 0;
      }
      ++attributes;
    }
    if (attributes == 0) {
      if (multipart && part > 0) break;  // the empty header after a multi-part file's last
      return "a header without attributes";
    }
    // Deep scanline chunks hold one line each.
    if (facts.deep && facts.tile_x == 0) facts.compression = 0;
    tables += 8 * chunk_count(facts);
    if (tables > size) return "the data window implies more chunks than the file has bytes for";
    if (!multipart) break;
  }
  return core_parse_problem(path);
}

}  // namespace kiln
