#include "job/frame_range.h"

#include <cstdio>
#include <regex>

#include "core/error.h"
#include "job/render_options.h"

namespace kiln {

namespace {

// Where the file name starts: placeholders in the folder part are left alone.
size_t file_name_start(const std::string& pattern) {
  const size_t slash = pattern.find_last_of('/');
  return slash == std::string::npos ? 0 : slash + 1;
}

// The last run of '#' in the file name: [begin, end), or begin == end when none.
std::pair<size_t, size_t> hash_run(const std::string& pattern) {
  const size_t start = file_name_start(pattern);
  const size_t last = pattern.find_last_of('#');
  if (last == std::string::npos || last < start) return {0, 0};
  size_t begin = last;
  while (begin > start && pattern[begin - 1] == '#') --begin;
  return {begin, last + 1};
}

// The last %d or %0Nd in the file name: [begin, end) and its width, or begin == end when none.
struct printf_field {
  size_t begin = 0, end = 0;
  int width = 0;
};

printf_field printf_run(const std::string& pattern) {
  static const std::regex field("%(0[1-9][0-9]?)?d");
  printf_field found;
  const std::string name = pattern.substr(file_name_start(pattern));
  for (auto it = std::sregex_iterator(name.begin(), name.end(), field); it != std::sregex_iterator(); ++it) {
    found.begin = file_name_start(pattern) + size_t(it->position());
    found.end = found.begin + size_t(it->length());
    found.width = (*it)[1].matched ? std::stoi((*it)[1].str()) : 0;
  }
  return found;
}

}  // namespace

frame_range parse_frame_range(const std::string& text) {
  static const std::regex form(R"((-?[0-9]{1,10})(?:-(-?[0-9]{1,10}))?(?::([0-9]{1,10}))?)");
  std::smatch m;
  if (!std::regex_match(text, m, form))
    throw input_error("", "--frames",
                      "expected FIRST-LAST[:STEP] (e.g. 1-240 or 1-240:2) or one frame, got '" + text + "'");
  frame_range r;
  r.first = std::stoll(m[1].str());
  r.last = m[2].matched ? std::stoll(m[2].str()) : r.first;
  r.step = m[3].matched ? std::stoll(m[3].str()) : 1;
  for (long long frame : {r.first, r.last})
    if (frame < -max_frame_number || frame > max_frame_number)
      throw input_error("", "--frames", "frames must lie within ±" + std::to_string(max_frame_number));
  if (r.last < r.first)
    throw input_error(
        "", "--frames",
        "the last frame " + std::to_string(r.last) + " comes before the first " + std::to_string(r.first));
  if (r.step < 1) throw input_error("", "--frames", "the step must be at least 1");
  if ((r.last - r.first) / r.step + 1 > max_sequence_frames)
    throw input_error("", "--frames",
                      "at most " + std::to_string(max_sequence_frames) + " frames in one sequence");
  return r;
}

std::vector<long long> frame_numbers(const frame_range& range) {
  std::vector<long long> frames;
  for (long long f = range.first; f <= range.last; f += range.step) frames.push_back(f);
  return frames;
}

bool has_frame_placeholder(const std::string& pattern) {
  const auto hashes = hash_run(pattern);
  const printf_field field = printf_run(pattern);
  return hashes.first != hashes.second || field.begin != field.end;
}

std::string frame_path(const std::string& pattern, long long frame) {
  const auto hashes = hash_run(pattern);
  const printf_field field = printf_run(pattern);
  // Of the two kinds, the one nearer the end of the name is the frame's.
  const bool use_hashes =
      hashes.first != hashes.second && (field.begin == field.end || hashes.first > field.begin);
  size_t begin = 0, end = 0;
  int width = 0;
  if (use_hashes) {
    begin = hashes.first;
    end = hashes.second;
    width = int(end - begin);
  } else if (field.begin != field.end) {
    begin = field.begin;
    end = field.end;
    width = field.width;
  } else {
    return pattern;
  }
  char digits[32];
  std::snprintf(digits, sizeof digits, "%0*lld", width, frame);
  return pattern.substr(0, begin) + digits + pattern.substr(end);
}

}  // namespace kiln
