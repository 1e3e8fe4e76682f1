// Small helpers shared by the glTF loader's files: JSON pointers for error messages and
// overflow-checked size arithmetic. Internal to io/gltf; depends on core/message_text.h and the
// standard library only.
#pragma once

#include <cctype>
#include <cstdint>
#include <limits>
#include <string>

#include "core/message_text.h"

namespace kiln::gltf_internal {

// Escapes one JSON-pointer token (RFC 6901: '~' -> "~0", '/' -> "~1"), as a message shows it
// (a key of 8 MB is cut short, see core/message_text.h).
inline std::string pointer_token(const std::string& token) {
  std::string out;
  for (char c : token) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return shown(out);
}

// "/<collection>/<index>", e.g. /accessors/7.
inline std::string pointer(const char* collection, int64_t index) {
  return std::string("/") + collection + "/" + std::to_string(index);
}

// Appends a key to a pointer: pointer_join("/nodes/2", "children") -> /nodes/2/children.
inline std::string pointer_join(const std::string& base, const std::string& key) {
  return base + "/" + pointer_token(key);
}

inline std::string pointer_join(const std::string& base, int64_t index) {
  return base + "/" + std::to_string(index);
}

// a + b without wrap-around; false when the sum does not fit in 64 bits.
inline bool checked_add(uint64_t a, uint64_t b, uint64_t& out) {
  if (a > std::numeric_limits<uint64_t>::max() - b) return false;
  out = a + b;
  return true;
}

// a * b without wrap-around; false when the product does not fit in 64 bits.
inline bool checked_mul(uint64_t a, uint64_t b, uint64_t& out) {
  if (a != 0 && b > std::numeric_limits<uint64_t>::max() / a) return false;
  out = a * b;
  return true;
}

// Decodes %XX escapes (RFC 3986) so that "%2E%2E/" cannot hide a ".." from the folder check.
inline std::string percent_decoded(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace kiln::gltf_internal
