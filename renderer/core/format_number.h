// Numbers quoted in messages, one format for every module: an ostream's default form (up to six
// significant digits, no trailing zeros: -0.5, 0.1, 1e+30, nan), as a person would write the
// value that was read. Depends on the standard library only.
#pragma once

#include <sstream>
#include <string>

namespace kiln {

// The shortest readable form of v for an error or test message (-0.5, not -0.500000).
inline std::string format_number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace kiln
