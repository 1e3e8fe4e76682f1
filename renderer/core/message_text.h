// User text inside kiln's one-line messages: URIs, names and values read from a file or typed on
// the command line. Control characters are escaped, so a name holding a newline cannot split the
// line, and text past max_shown_bytes is cut with an ellipsis and its full length, so an 8 MB URI
// cannot flood a log. Every message that echoes such text goes through quoted() or shown().
// Depends on the standard library only.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>

namespace kiln {

// How much of one piece of user text a message shows.
constexpr size_t max_shown_bytes = 200;

namespace message_text_detail {

// The first `limit` bytes or fewer, never ending inside a UTF-8 sequence.
inline size_t cut_point(const std::string& text, size_t limit) {
  if (text.size() <= limit) return text.size();
  size_t cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return cut;
}

inline std::string escaped(const std::string& text, size_t end) {
  std::string out;
  out.reserve(end);
  for (size_t i = 0; i < end; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c != 0x7F) {
      out += static_cast<char>(c);
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    }
  }
  return out;
}

}  // namespace message_text_detail

// The text as a message shows it: "abc", or "aaaa... (8000004 bytes)" when it is too long.
inline std::string shown(const std::string& text) {
  const size_t end = message_text_detail::cut_point(text, max_shown_bytes);
  std::string out = message_text_detail::escaped(text, end);
  if (end < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

// The text in single quotes: "'abc'", or "'aaaa...' (8000004 bytes)" when it is too long.
inline std::string quoted(const std::string& text) {
  const size_t end = message_text_detail::cut_point(text, max_shown_bytes);
  const std::string head = message_text_detail::escaped(text, end);
  if (end == text.size()) return "'" + head + "'";
  return "'" + head + "...' (" + std::to_string(text.size()) + " bytes)";
}

}  // namespace kiln
