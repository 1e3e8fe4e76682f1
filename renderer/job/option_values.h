// Text to values for the option table, with the checks every option shares: integers that are
// whole text (base 0, as "0x10" and "010" read), finite numbers in a range (NaN passes no
// comparison, so it is refused first), choices, and X,Y,Z triples. Each throws kiln::error
// (input) whose location is the option ("--spp") and whose reason names what was expected and
// what was given. Printing goes the other way: exactly enough digits to read back the same value.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"

namespace kiln {

long long parse_integer(const std::string& text, const std::string& option, long long min, long long max);
unsigned long long parse_unsigned(const std::string& text, const std::string& option, unsigned long long min,
                                  unsigned long long max);
// A size in bytes: an integer, or one followed by K, M, G or T (binary: 1K = 1024; "KiB" and
// "KB" read the same), at least 1 byte. "4G" is 4294967296.
uint64_t parse_memory_size(const std::string& text, const std::string& option);
// A finite number in [min, max]; with min_exclusive, in (min, max].
double parse_number(const std::string& text, const std::string& option, double min, double max,
                    bool min_exclusive = false);
// "true"/"on"/"1" or "false"/"off"/"0".
bool parse_flag(const std::string& text, const std::string& option);
void check_choice(const std::string& text, const std::string& option,
                  const std::vector<std::string>& choices);
// "X,Y,Z": three finite numbers.
dvec3 parse_triple(const std::string& text, const std::string& option);

// --shutter's "OPEN,CLOSE": two finite frame offsets within ±1e6, OPEN before CLOSE.
std::pair<double, double> parse_shutter(const std::string& text);
// The most time steps Embree interpolates between (RTC_MAX_TIME_STEP_COUNT).
constexpr int max_motion_steps = 129;

std::string exact_text(double value);  // %.17g
std::string exact_text(float value);   // %.9g
template <typename V>
std::string triple_text(const V& v) {
  return exact_text(v.x) + "," + exact_text(v.y) + "," + exact_text(v.z);
}

}  // namespace kiln
