#include "io/exr/exr_message.h"

namespace kiln {

std::string exr_message(std::string what, const std::string& path) {
  const std::string quoted = " \"" + path + "\"";
  for (size_t at = what.find(quoted); !path.empty() && at != std::string::npos; at = what.find(quoted, at))
    what.erase(at, quoted.size());
  for (char& c : what) {
    if (c == '\n' || c == '\t') c = ' ';
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
  }
  return what;
}

}  // namespace kiln
