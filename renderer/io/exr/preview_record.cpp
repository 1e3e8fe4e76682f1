#include "io/exr/preview_record.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "io/exr/exr_checksum.h"
#include "io/exr/preview_writer.h"

namespace kiln {

namespace {

const char keyword[] = "kiln/checksum";  // also the text's start in a JPEG comment

uint32_t big_endian(const unsigned char* p, int bytes) {
  uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | p[i];
  return v;
}

void put_big_endian(std::vector<unsigned char>& out, uint32_t v, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) out.push_back((unsigned char)(v >> (8 * i)));
}

// Where the record is, or goes: [begin, end) of bytes.
struct span {
  size_t begin = 0, end = 0;
  bool found = false;
};

// The keyword and its separator (PNG: NUL, JPEG: a space), then the value.
bool starts_with_keyword(const unsigned char* data, size_t size, char separator) {
  return size > sizeof keyword && std::memcmp(data, keyword, sizeof keyword - 1) == 0 &&
         data[sizeof keyword - 1] == (unsigned char)separator;
}

// PNG: chunks after the 8-byte signature (length, type, data, CRC) up to the first IDAT; the record
// goes after IHDR (the first chunk).
span find_png(const std::vector<unsigned char>& bytes) {
  span s;
  size_t at = 8;
  bool first = true;
  while (at + 12 <= bytes.size()) {
    const size_t length = big_endian(&bytes[at], 4);
    if (length > bytes.size() - at - 12) break;
    const unsigned char* type = &bytes[at + 4];
    const size_t next = at + 12 + length;
    if (std::memcmp(type, "IDAT", 4) == 0) break;
    if (std::memcmp(type, "tEXt", 4) == 0 && starts_with_keyword(&bytes[at + 8], length, '\0'))
      return {at, next, true};
    if (first) s.begin = s.end = next;
    first = false;
    at = next;
  }
  return s;
}

// JPEG: marker segments after SOI (FF D8) up to the scan (FF DA); the record goes after JFIF's
// APP0 when there is one, else right after SOI.
span find_jpeg(const std::vector<unsigned char>& bytes) {
  span s{2, 2, false};
  size_t at = 2;
  while (at + 4 <= bytes.size() && bytes[at] == 0xFF) {
    const unsigned char marker = bytes[at + 1];
    if (marker == 0xDA) break;
    const size_t length = big_endian(&bytes[at + 2], 2);  // counts itself
    if (length < 2 || length > bytes.size() - at - 2) break;
    const size_t next = at + 2 + length;
    if (marker == 0xFE && starts_with_keyword(&bytes[at + 4], length - 2, ' ')) return {at, next, true};
    if (marker == 0xE0 && at == 2) s.begin = s.end = next;
    at = next;
  }
  return s;
}

span find_record(const std::vector<unsigned char>& bytes, const std::string& format) {
  return format == "png" ? find_png(bytes) : find_jpeg(bytes);
}

// The CRC of bytes without [skip.begin, skip.end).
std::string checksum_without(const std::vector<unsigned char>& bytes, const span& skip) {
  content_crc crc;
  crc.add(bytes.data(), skip.begin);
  crc.add(bytes.data() + skip.end, bytes.size() - skip.end);
  return crc.text();
}

}  // namespace

std::vector<unsigned char> with_checksum_record(const std::vector<unsigned char>& encoded,
                                                const std::string& format) {
  const span at = find_record(encoded, format);
  const std::string value = checksum_without(encoded, {at.begin, at.begin, false});
  std::vector<unsigned char> record;
  if (format == "png") {
    std::vector<unsigned char> chunk = {'t', 'E', 'X', 't'};
    chunk.insert(chunk.end(), keyword, keyword + sizeof keyword);  // with its NUL separator
    chunk.insert(chunk.end(), value.begin(), value.end());
    put_big_endian(record, uint32_t(chunk.size() - 4), 4);
    record.insert(record.end(), chunk.begin(), chunk.end());
    content_crc crc;
    crc.add(chunk.data(), chunk.size());
    put_big_endian(record, crc.value, 4);
  } else {
    const std::string text = std::string(keyword) + " " + value;
    record = {0xFF, 0xFE};
    put_big_endian(record, uint32_t(text.size() + 2), 2);
    record.insert(record.end(), text.begin(), text.end());
  }
  std::vector<unsigned char> out(encoded.begin(), encoded.begin() + std::ptrdiff_t(at.begin));
  out.insert(out.end(), record.begin(), record.end());
  out.insert(out.end(), encoded.begin() + std::ptrdiff_t(at.begin), encoded.end());
  return out;
}

std::string checksum_record_problem(const std::vector<unsigned char>& bytes, const std::string& format) {
  const span at = find_record(bytes, format);
  if (!at.found) return std::string("no ") + keyword + " record (written before kiln recorded one)";
  if (format == "png") {  // the chunk's own CRC, of its type and data
    content_crc chunk;
    chunk.add(&bytes[at.begin + 4], at.end - at.begin - 8);
    if (chunk.value != big_endian(&bytes[at.end - 4], 4))
      return std::string("its ") + keyword + " chunk is damaged";
  }
  // PNG: after the keyword's NUL; JPEG: after the keyword and a space.
  const size_t text = at.begin + (format == "png" ? 8 : 4) + sizeof keyword;
  const size_t text_end = at.end - (format == "png" ? 4 : 0);
  const std::string recorded(bytes.begin() + std::ptrdiff_t(text), bytes.begin() + std::ptrdiff_t(text_end));
  const std::string read = checksum_without(bytes, at);
  if (read != recorded)
    return "its bytes read back as " + read + ", not the recorded " + keyword + " " + recorded +
           " (damaged or edited)";
  return "";
}

std::string preview_file_problem(const std::string& path, int width, int height) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return "missing";
  if (!std::filesystem::is_regular_file(path, ec)) return "not a regular file";
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  if (!in.eof() && !in) return "cannot be read";
  const std::string format = preview_format(path);
  if (format.empty()) return "not a .png, .jpg or .jpeg";
  std::string problem = checksum_record_problem(bytes, format);
  if (problem.empty() && !preview_complete(path, width, height))
    problem = "does not decode completely as a " + std::to_string(width) + "x" + std::to_string(height) +
              " " + format + " (the EXR's data window)";
  return problem;
}

}  // namespace kiln
