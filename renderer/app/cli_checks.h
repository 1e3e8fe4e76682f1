// Option checks shared by every subcommand.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <string>

namespace kiln {

// CLI11's Range and NonNegativeNumber compare with < and >, which NaN passes, so every floating
// option takes this check first: "nan", "inf" and overflowing text such as 1e999 are usage errors
// (exit 2) instead of values that reach the camera or the image.
inline CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        const double value = std::strtod(begin, &end);
        if (end == begin) return {};  // not a number at all: the option's own conversion reports it
        if (!std::isfinite(value)) return "expects a finite number, got '" + text + "'";
        return {};
      },
      "");
}

}  // namespace kiln
