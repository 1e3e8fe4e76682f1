#include "job/option_entries.h"

#include <sys/stat.h>

#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "job/asset_file.h"
#include "render/aov_table.h"

namespace kiln::option_entries {

namespace fs = std::filesystem;

namespace {

void check_existing_file(const std::string& path, const std::string& option) {
  check_no_nul(path, option);
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0) throw input_error("", option, "no such file '" + path + "'");
  if (S_ISDIR(s.st_mode)) throw input_error("", option, "'" + path + "' is a folder, not a file");
}

}  // namespace

option_spec choice_option(const std::string& name, field<std::string> at, std::vector<std::string> choices,
                          const std::string& example, const std::string& help) {
  option_spec s;
  s.name = name;
  s.help = help;
  s.example = example;
  s.choices = choices;
  s.set = [at, name, choices](render_options& o, const std::string& text) {
    check_choice(text, dashed(name), choices);
    at(o) = text;
  };
  s.get = [at](const render_options& o) -> std::optional<std::string> { return read(o, at); };
  return s;
}

option_spec flag_option(const std::string& name, field<bool> at, const std::string& help) {
  option_spec s;
  s.name = name;
  s.type = option_type::flag;
  s.help = help;
  s.example = "true";
  s.set = [at, name](render_options& o, const std::string& text) { at(o) = parse_flag(text, dashed(name)); };
  s.get = [at](const render_options& o) -> std::optional<std::string> {
    return std::string(read(o, at) ? "true" : "false");
  };
  return s;
}

option_spec custom_option(const std::string& name,
                          std::function<void(render_options&, const std::string&)> set,
                          std::function<std::optional<std::string>(const render_options&)> get,
                          const std::string& example, const std::string& help) {
  option_spec s;
  s.name = name;
  s.help = help;
  s.example = example;
  s.set = std::move(set);
  s.get = std::move(get);
  return s;
}

option_spec file_option(const std::string& name, std::string render_options::*at, const std::string& help) {
  option_spec s = custom_option(
      name,
      [name, at](render_options& o, const std::string& text) {
        check_existing_file(text, dashed(name));
        o.*at = text;
      },
      [at](const render_options& o) -> std::optional<std::string> {
        if ((o.*at).empty()) return std::nullopt;
        return fs::absolute(o.*at).lexically_normal().string();
      },
      "", help);
  s.names_file = true;
  return s;
}

option_spec optional_side(const std::string& name, field<std::optional<int>> at, const std::string& example,
                          const std::string& help) {
  option_spec s = custom_option(
      name,
      [at, name](render_options& o, const std::string& text) {
        at(o) = int(parse_integer(text, dashed(name), 1, max_image_side));
      },
      [at](const render_options& o) -> std::optional<std::string> {
        const std::optional<int>& v = read(o, at);
        return v ? std::optional<std::string>(std::to_string(*v)) : std::nullopt;
      },
      example, help);
  s.type = option_type::integer;
  return s;
}

option_spec optional_triple(const std::string& name, field<std::optional<dvec3>> at,
                            const std::string& example, const std::string& help) {
  return custom_option(
      name,
      [at, name](render_options& o, const std::string& text) { at(o) = parse_triple(text, dashed(name)); },
      [at](const render_options& o) -> std::optional<std::string> {
        const std::optional<dvec3>& v = read(o, at);
        return v ? std::optional<std::string>(triple_text(*v)) : std::nullopt;
      },
      example, help);
}

glm::ivec3 parse_grid_resolution(const std::string& text) {
  std::istringstream in(text);
  glm::ivec3 r;
  char comma1 = 0, comma2 = 0;
  bool ok = bool(in >> r.x);
  if (ok && (in >> std::ws).eof()) {
    r = glm::ivec3(r.x);
  } else {
    in.clear();
    ok = ok && (in >> comma1 >> r.y >> comma2 >> r.z) && comma1 == ',' && comma2 == ',' &&
         (in >> std::ws).eof();
  }
  if (!ok || glm::any(glm::lessThan(r, glm::ivec3(1))) ||
      glm::any(glm::greaterThan(r, glm::ivec3(max_grid_resolution))))
    throw input_error("", "--grid-resolution",
                      "expects N or X,Y,Z cells per axis, each 1 to " + std::to_string(max_grid_resolution) +
                          ", got '" + text + "'");
  return r;
}

pixel_rect parse_crop(const std::string& text) {
  std::istringstream in(text);
  pixel_rect r;
  char c1 = 0, c2 = 0, c3 = 0;
  if (!(in >> r.x0 >> c1 >> r.y0 >> c2 >> r.x1 >> c3 >> r.y1) || c1 != ',' || c2 != ',' || c3 != ',' ||
      !(in >> std::ws).eof() || r.x0 < 0 || r.y0 < 0 || r.x1 <= r.x0 || r.y1 <= r.y0)
    throw input_error("", "--crop",
                      "expects pixels x0,y0,x1,y1 with 0 <= x0 < x1 and 0 <= y0 < y1, got '" + text + "'");
  return r;
}

void parse_band(render_options& o, const std::string& text) {
  std::istringstream in(text);
  char slash = 0;
  int index = -1, count = 0;
  if (!(in >> index >> slash >> count) || slash != '/' || !(in >> std::ws).eof() || count < 1 || index < 0 ||
      index >= count)
    throw input_error("", "--band", "expects I/N with N >= 1 and 0 <= I < N, got '" + text + "'");
  o.band_index = index;
  o.band_count = count;
}

void parse_aovs(render_options& o, const std::string& text) {
  std::string bad;
  std::optional<aov_set> aovs = parse_aov_list(text, &bad);
  if (!aovs)
    throw input_error("", "--aovs",
                      "unknown or repeated output " + bad + " (choose from " + aov_name_list() + ")");
  // --cryptomatte-depth and --depth-mode fill in fields of the same set, whichever comes first.
  aovs->crypto_depth = o.aovs.crypto_depth;
  aovs->depth_kind = o.aovs.depth_kind;
  o.aovs = *aovs;
}

std::vector<std::string> quality_names() {
  return {bvh_quality_name(bvh_quality::low), bvh_quality_name(bvh_quality::medium),
          bvh_quality_name(bvh_quality::high)};
}

}  // namespace kiln::option_entries
