#include "job/option_values.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "core/error.h"
#include "core/message_text.h"

namespace kiln {

namespace {

[[noreturn]] void refuse(const std::string& option, const std::string& reason) {
  throw input_error("", option, reason);
}

}  // namespace

long long parse_integer(const std::string& text, const std::string& option, long long min, long long max) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(begin, &end, 0);
  if (end == begin || *end != '\0') refuse(option, "expects an integer, got " + quoted(text));
  if (errno == ERANGE) refuse(option, "expects an integer, got " + quoted(text) + ", which is too large");
  if (value < min || value > max)
    refuse(option, "expects an integer from " + std::to_string(min) + " to " + std::to_string(max) +
                       ", got " + quoted(text));
  return value;
}

unsigned long long parse_unsigned(const std::string& text, const std::string& option, unsigned long long min,
                                  unsigned long long max) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(begin, &end, 0);
  // strtoull reads "-3" as a huge number: a sign is refused outright.
  if (end == begin || *end != '\0' || text.find('-') != std::string::npos)
    refuse(option, "expects a non-negative integer, got " + quoted(text));
  if (errno == ERANGE) refuse(option, "expects an integer, got " + quoted(text) + ", which is too large");
  if (value < min || value > max)
    refuse(option, "expects an integer from " + std::to_string(min) + " to " + std::to_string(max) +
                       ", got " + quoted(text));
  return value;
}

uint64_t parse_memory_size(const std::string& text, const std::string& option) {
  const auto expected = [&] {
    refuse(option, "expects a size in bytes, optionally with K, M, G or T (binary), got " + quoted(text));
  };
  size_t digits = 0;
  while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) ++digits;
  if (digits == 0) expected();
  std::string unit = text.substr(digits);
  for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
  if (unit == "B") unit.clear();
  if (unit.size() == 3 && unit.substr(1) == "IB") unit.resize(1);
  if (unit.size() == 2 && unit[1] == 'B') unit.resize(1);
  const std::string units = "KMGT";
  if (unit.size() > 1 || (unit.size() == 1 && units.find(unit[0]) == std::string::npos)) expected();
  const size_t power = unit.empty() ? 0 : units.find(unit[0]) + 1;
  errno = 0;
  const unsigned long long value = std::strtoull(text.substr(0, digits).c_str(), nullptr, 10);
  const int shift = int(power) * 10;
  if (errno == ERANGE || (shift > 0 && value > (~0ull >> shift)))
    refuse(option, "expects a size below 16 EiB, got " + quoted(text));
  if (value == 0) refuse(option, "expects a size of at least 1 byte, got " + quoted(text));
  return uint64_t(value) << shift;
}

double parse_number(const std::string& text, const std::string& option, double min, double max,
                    bool min_exclusive) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin || *end != '\0') refuse(option, "expects a number, got " + quoted(text));
  if (!std::isfinite(value)) refuse(option, "expects a finite number, got " + quoted(text));
  const bool above_min = min_exclusive ? value > min : value >= min;
  if (!above_min || value > max)
    refuse(option, std::string("expects a number ") + (min_exclusive ? "in (" : "from ") + exact_text(min) +
                       (min_exclusive ? ", " : " to ") + exact_text(max) + (min_exclusive ? "]" : "") +
                       ", got " + quoted(text));
  return value;
}

bool parse_flag(const std::string& text, const std::string& option) {
  if (text == "true" || text == "on" || text == "1") return true;
  if (text == "false" || text == "off" || text == "0") return false;
  refuse(option, "is a flag: expects true or false, got " + quoted(text));
}

void check_choice(const std::string& text, const std::string& option,
                  const std::vector<std::string>& choices) {
  std::string list;
  for (const std::string& choice : choices) {
    if (choice == text) return;
    list += (list.empty() ? "" : ", ") + choice;
  }
  refuse(option, "expects one of " + list + ", got " + quoted(text));
}

dvec3 parse_triple(const std::string& text, const std::string& option) {
  dvec3 value;
  std::istringstream in(text);
  char comma1 = 0, comma2 = 0;
  if (!(in >> value.x >> comma1 >> value.y >> comma2 >> value.z) || comma1 != ',' || comma2 != ',' ||
      !(in >> std::ws).eof() || !is_finite(value))
    refuse(option, "expects three finite numbers X,Y,Z, got " + quoted(text));
  return value;
}

std::pair<double, double> parse_shutter(const std::string& text) {
  std::pair<double, double> shutter;
  std::istringstream in(text);
  char comma = 0;
  if (!(in >> shutter.first >> comma >> shutter.second) || comma != ',' || !(in >> std::ws).eof() ||
      !std::isfinite(shutter.first) || !std::isfinite(shutter.second))
    refuse("--shutter", "expects two finite frame offsets OPEN,CLOSE (e.g. -0.25,0.25), got " + quoted(text));
  if (std::abs(shutter.first) > 1e6 || std::abs(shutter.second) > 1e6)
    refuse("--shutter", "frame offsets must lie within -1e6 and 1e6, got " + quoted(text));
  if (!(shutter.first < shutter.second))
    refuse("--shutter", "the shutter must open before it closes, got " + quoted(text));
  return shutter;
}

std::string exact_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string exact_text(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(value));
  return text;
}

}  // namespace kiln
