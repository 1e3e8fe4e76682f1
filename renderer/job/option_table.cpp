#include "job/option_table.h"

#include "core/error.h"
#include "job/option_entries.h"
#include "job/option_values.h"

namespace kiln {

namespace {

using option_entries::dashed;

std::vector<option_spec> make_table() {
  std::vector<option_spec> t;
  option_entries::add_view_options(t);
  option_entries::add_trace_options(t);
  option_entries::add_image_options(t);
  option_entries::add_progress_options(t);
  return t;
}

std::string bare_name(const std::string& name) {
  size_t dashes = 0;
  while (dashes < name.size() && dashes < 2 && name[dashes] == '-') ++dashes;
  return name.substr(dashes);
}

// The canonical text get() gave (exact digits, so the numbers read back as they were set) as the
// attribute value spec.recorded_type says.
exr_value recorded_value(const option_spec& spec, const std::string& text) {
  switch (spec.recorded_type) {
    case record_type::float64:
      return std::stod(text);
    case record_type::float2: {
      const size_t comma = text.find(',');
      return vec2(float(std::stod(text.substr(0, comma))), float(std::stod(text.substr(comma + 1))));
    }
    case record_type::float3:
      return vec3(parse_triple(text, dashed(spec.name)));
    case record_type::by_type:
      break;
  }
  switch (spec.type) {
    case option_type::integer:
    case option_type::unsigned_integer:
      return int(std::stoll(text));  // every recorded integer's range fits an int
    case option_type::number:
      return float(std::stod(text));
    case option_type::flag:
      return std::string(text == "true" ? "on" : "off");
    case option_type::text:
      break;
  }
  return text;
}

struct group_heading {
  option_group group;
  const char* title;
};

// The groups in order, with their headings.
constexpr group_heading group_headings[] = {
    {option_group::output, "Output"},
    {option_group::camera, "Camera and scene"},
    {option_group::sampling, "Sampling"},
    {option_group::lighting, "Lighting"},
    {option_group::aovs, "AOVs"},
    {option_group::animation, "Animation"},
    {option_group::layers, "Render layers"},
    {option_group::colour, "Colour"},
    {option_group::performance, "Performance"},
    {option_group::progress, "Progress"},
    {option_group::limits, "Limits"},
};

}  // namespace

const std::vector<option_group>& option_groups() {
  static const std::vector<option_group> groups = [] {
    std::vector<option_group> in_order;
    for (const group_heading& heading : group_headings) in_order.push_back(heading.group);
    return in_order;
  }();
  return groups;
}

const char* option_group_title(option_group group) {
  for (const group_heading& heading : group_headings)
    if (heading.group == group) return heading.title;
  return "Unassigned";
}

const std::vector<option_spec>& render_option_table() {
  static const std::vector<option_spec> table = make_table();
  return table;
}

const option_spec* find_render_option(const std::string& name) {
  const std::string bare = bare_name(name);
  for (const option_spec& spec : render_option_table())
    if (spec.name == bare || (!spec.alias.empty() && spec.alias == bare) ||
        (!spec.short_name.empty() && spec.short_name == bare))
      return &spec;
  return nullptr;
}

void set_render_option(render_options& options, const std::string& name, const std::string& text) {
  const option_spec* spec = find_render_option(name);
  if (!spec) throw input_error("", dashed(bare_name(name)), "is not a render option");
  spec->set(options, text);
}

std::vector<std::string> canonical_render_arguments(const render_options& options, region_arguments region) {
  std::vector<std::string> arguments;
  for (const option_spec& spec : render_option_table()) {
    if (spec.effect == option_effect::none) continue;
    if (spec.effect == option_effect::region && region == region_arguments::omit) continue;
    const std::optional<std::string> value = spec.get(options);
    if (!value) continue;
    if (spec.type == option_type::flag) {
      if (*value == "true") arguments.push_back(dashed(spec.name));
      continue;
    }
    arguments.push_back(dashed(spec.name));
    arguments.push_back(*value);
  }
  return arguments;
}

std::vector<std::pair<std::string, exr_value>> recorded_option_attributes(const render_options& options) {
  std::vector<std::pair<std::string, exr_value>> attributes;
  for (const option_spec& spec : render_option_table()) {
    if (spec.recorded_as.empty()) continue;
    const std::optional<std::string> value = spec.get(options);
    if (value) attributes.emplace_back(spec.recorded_as, recorded_value(spec, *value));
  }
  return attributes;
}

}  // namespace kiln
