#include "app/text_output.h"

#include "io/exr/atomic_write.h"

namespace kiln {

void write_text_atomically(const std::string& path, const std::string& text) {
  // The writer the images use: a temporary name no other write shares, created by this call (never
  // a file or link placed at a guessable name), fsynced, renamed into place.
  write_atomically(path, "the file", [&](const temporary_file& temporary) {
    return write_all(temporary.fd, text.data(), text.size());
  });
}

namespace {

// value as dump(2) writes it at depth levels down.
std::string indented(const nlohmann::json& value, int depth) {
  std::string text = value.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
  const std::string indent(size_t(depth) * 2, ' ');
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    out += c;
    if (c == '\n') out += indent;
  }
  return out;
}

}  // namespace

void write_json_list_atomically(const std::string& path, const nlohmann::json& object,
                                const std::string& list_key, size_t count,
                                const std::function<nlohmann::json(size_t)>& item) {
  nlohmann::json keys = object;
  keys[list_key] = nullptr;  // its place among the keys, which dump writes sorted
  write_atomically(path, "the file", [&](const temporary_file& temporary) {
    std::string text = "{";
    const auto flush = [&] {
      std::string reason = write_all(temporary.fd, text.data(), text.size());
      text.clear();
      return reason;
    };
    bool first_key = true;
    for (const auto& [key, value] : keys.items()) {
      text += std::string(first_key ? "" : ",") + "\n  " + nlohmann::json(key).dump() + ": ";
      first_key = false;
      if (key != list_key) {
        text += indented(value, 1);
        continue;
      }
      if (count == 0) {
        text += "[]";
        continue;
      }
      text += "[";
      for (size_t i = 0; i < count; ++i) {
        text += std::string(i ? "," : "") + "\n    " + indented(item(i), 2);
        if (text.size() >= (size_t(1) << 20))
          if (std::string reason = flush(); !reason.empty()) return reason;
      }
      text += "\n  ]";
    }
    text += "\n}\n";
    return flush();
  });
}

}  // namespace kiln
