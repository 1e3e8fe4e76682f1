// The option table's building blocks, shared by the files that fill its parts (view_options.cpp,
// trace_options.cpp, image_options.cpp): one builder per kind of option_spec (integer, number,
// choice, flag, file, ...), the parsers of the options whose text has its own form, and the
// functions adding each part's entries. Only the option table's own files include it.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "job/option_table.h"
#include "job/option_values.h"

namespace kiln::option_entries {

template <typename T>
using field = std::function<T&(render_options&)>;

// Reads a field through its accessor without a second, const accessor for every entry.
template <typename T>
const T& read(const render_options& o, const field<T>& at) {
  return at(const_cast<render_options&>(o));
}

inline std::string dashed(const std::string& name) { return "--" + name; }

constexpr int max_image_side = 65536;
// Bounds of the --grid-* options: beyond them a grid's memory explodes (256³ cells per grid, 8^depth
// children per crowded cell) long before traversal gets faster.
constexpr int max_grid_resolution = 256;
constexpr int max_grid_depth = 6;

template <typename T>
option_spec integer_option(const std::string& name, field<T> at, long long min, long long max,
                           const std::string& example, const std::string& help) {
  option_spec s;
  s.name = name;
  s.type = option_type::integer;
  s.help = help;
  s.example = example;
  s.set = [at, name, min, max](render_options& o, const std::string& text) {
    at(o) = T(parse_integer(text, dashed(name), min, max));
  };
  s.get = [at](const render_options& o) -> std::optional<std::string> { return std::to_string(read(o, at)); };
  return s;
}

template <typename T>
option_spec unsigned_option(const std::string& name, field<T> at, unsigned long long min,
                            unsigned long long max, const std::string& example, const std::string& help) {
  option_spec s;
  s.name = name;
  s.type = option_type::unsigned_integer;
  s.help = help;
  s.example = example;
  s.set = [at, name, min, max](render_options& o, const std::string& text) {
    at(o) = T(parse_unsigned(text, dashed(name), min, max));
  };
  s.get = [at](const render_options& o) -> std::optional<std::string> { return std::to_string(read(o, at)); };
  return s;
}

template <typename T>
option_spec number_option(const std::string& name, field<T> at, double min, double max,
                          const std::string& example, const std::string& help) {
  option_spec s;
  s.name = name;
  s.type = option_type::number;
  s.help = help;
  s.example = example;
  s.set = [at, name, min, max](render_options& o, const std::string& text) {
    at(o) = T(parse_number(text, dashed(name), min, max));
  };
  s.get = [at](const render_options& o) -> std::optional<std::string> { return exact_text(read(o, at)); };
  return s;
}

option_spec choice_option(const std::string& name, field<std::string> at, std::vector<std::string> choices,
                          const std::string& example, const std::string& help);
option_spec flag_option(const std::string& name, field<bool> at, const std::string& help);
// A text option with its own parser and printer.
option_spec custom_option(const std::string& name,
                          std::function<void(render_options&, const std::string&)> set,
                          std::function<std::optional<std::string>(const render_options&)> get,
                          const std::string& example, const std::string& help);
// An option naming a file that must exist, given back by absolute path: the same file named from
// another folder is the same setting. Its example is filled in by the table's tests.
option_spec file_option(const std::string& name, std::string render_options::*at, const std::string& help);
// An image side in pixels, unset unless given.
option_spec optional_side(const std::string& name, field<std::optional<int>> at, const std::string& example,
                          const std::string& help);
// Three numbers X,Y,Z, unset unless given.
option_spec optional_triple(const std::string& name, field<std::optional<dvec3>> at,
                            const std::string& example, const std::string& help);

// "N" (N cells on every axis) or "X,Y,Z" for --grid-resolution.
glm::ivec3 parse_grid_resolution(const std::string& text);
pixel_rect parse_crop(const std::string& text);
void parse_band(render_options& o, const std::string& text);
void parse_aovs(render_options& o, const std::string& text);
std::vector<std::string> quality_names();

// Appends the entries of one scope to the table, each in the group last set; gives back the entry
// added, for the fields set after it.
struct scoped_adder {
  std::vector<option_spec>& table;
  option_scope scope;
  option_group group = option_group::unassigned;
  option_spec& operator()(option_spec s) const {
    s.scope = scope;
    s.group = group;
    table.push_back(std::move(s));
    return table.back();
  }
};

// The table's parts, in the table's order (which is --help's): the camera, image size and pose;
// the scene's shading, limits and traversal; the EXR and its outputs; progress.
void add_view_options(std::vector<option_spec>& t);
void add_trace_options(std::vector<option_spec>& t);
void add_image_options(std::vector<option_spec>& t);
void add_progress_options(std::vector<option_spec>& t);

}  // namespace kiln::option_entries
