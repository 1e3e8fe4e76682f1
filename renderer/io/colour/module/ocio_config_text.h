// A linear pass over an OpenColorIO config's YAML text, made before OpenColorIO parses it.
// OpenColorIO 2.1 reads a config in time quadratic in its named entries (each new colour space,
// alias, named transform, look, view transform, view or display is checked against all before
// it: 20,000 colour spaces take it half a minute, 200,000 an hour), so kiln bounds their number
// first. Knows YAML's syntax, not OpenColorIO; depends on the standard library only.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace kiln::colour_module {

// What the pass found.
struct config_text_shape {
  // An upper bound on the entries OpenColorIO adds one at a time: every item of every sequence
  // (a vector of numbers under a numeric key such as matrix excepted) and every pair of the top
  // two mapping levels (the config's own keys, roles, displays, environment).
  uint64_t entries = 0;
  uint64_t colour_spaces = 0;  // !<ColorSpace> tags
  // Set when the text uses YAML that would defeat the count: anchors and aliases (a few bytes
  // naming a list again and again), %TAG directives (tags spelt other than !<ColorSpace>),
  // explicit keys, tabs in indentation. OpenColorIO's own writer uses none of them.
  std::string refusal;
};

// Scans the first YAML document of text, as yaml-cpp (OpenColorIO's parser) would read it, in
// time and memory linear in its size; counts err on the high side where the syntax is ambiguous.
config_text_shape scan_config_text(std::string_view text);

}  // namespace kiln::colour_module
