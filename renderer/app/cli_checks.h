// Option checks shared by every subcommand.
#pragma once

#include <CLI/CLI.hpp>
#include <cerrno>
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

// CLI11 runs an option's range check before converting its text, so "--spp abc" said "Value abc not
// in range 1 to 65536". This check comes first on every integer option (CLI11's type names INT and
// UINT) of app and its subcommands: text that is not an integer is a usage error that says so.
// Base 0 as CLI11's own conversion (0x10 and 010 read as it reads them).
inline void require_integer_text(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    const bool is_unsigned = type.rfind("UINT", 0) == 0;
    if (!is_unsigned && type.rfind("INT", 0) != 0) continue;
    option->transform(CLI::Validator(
        [is_unsigned](std::string& text) -> std::string {
          const char* begin = text.c_str();
          char* end = nullptr;
          errno = 0;
          if (is_unsigned)
            (void)std::strtoull(begin, &end, 0);
          else
            (void)std::strtoll(begin, &end, 0);
          const bool negative = text.find('-') != std::string::npos;
          if (end == begin || *end != '\0' || (is_unsigned && negative))
            return std::string("expects ") + (is_unsigned ? "a non-negative integer" : "an integer") +
                   ", got '" + text + "'";
          if (errno == ERANGE) return "expects an integer, got '" + text + "', which is too large";
          return {};
        },
        ""));
  }
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; }))
    require_integer_text(*command);
}

}  // namespace kiln
