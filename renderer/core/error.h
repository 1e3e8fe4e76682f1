// The one error type kiln throws at its boundaries (loaders, writers, CLI validation).
// It carries the file, the location inside it (a JSON pointer such as /accessors/7) and the
// reason, so the CLI can print exactly one line. Depends on the standard library only.
#pragma once

#include <stdexcept>
#include <string>

namespace kiln {

// What kind of failure: bad input maps to exit code 2, I/O or render failure to exit code 1, a
// render stopped by SIGINT/SIGTERM to 128 + the signal number, as shells report it, and one
// stopped by its --time-limit to 124, as timeout(1) reports it.
enum class error_kind { input, io, render, interrupted, time_limit };

class error : public std::runtime_error {
 public:
  error(error_kind kind, std::string file, std::string location, std::string reason)
      : std::runtime_error(format(file, location, reason)),
        kind_(kind),
        file_(std::move(file)),
        location_(std::move(location)),
        reason_(std::move(reason)) {}

  error_kind kind() const { return kind_; }
  const std::string& file() const { return file_; }
  const std::string& location() const { return location_; }
  const std::string& reason() const { return reason_; }

 private:
  static std::string format(const std::string& file, const std::string& location, const std::string& reason) {
    // The CLI prefixes "kiln: "; an error without a file is just its location and reason.
    std::string line = file;
    if (!location.empty()) line += (line.empty() ? "" : ": ") + location;
    return line.empty() ? reason : line + ": " + reason;
  }

  error_kind kind_;
  std::string file_;
  std::string location_;
  std::string reason_;
};

// Shorthand for bad input (exit code 2).
inline error input_error(const std::string& file, const std::string& location, const std::string& reason) {
  return error(error_kind::input, file, location, reason);
}

// Shorthand for an I/O failure (exit code 1).
inline error io_error(const std::string& file, const std::string& reason) {
  return error(error_kind::io, file, "", reason);
}

}  // namespace kiln
