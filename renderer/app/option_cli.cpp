#include "app/option_cli.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <set>

#include "core/error.h"
#include "job/retired_options.h"

namespace kiln {

namespace {

std::string type_name(const option_spec& spec) {
  if (!spec.choices.empty()) {
    std::string names;
    for (const std::string& choice : spec.choices) names += (names.empty() ? "" : "|") + choice;
    return names;
  }
  switch (spec.type) {
    case option_type::integer:
      return "INT";
    case option_type::unsigned_integer:
      return "UINT";
    case option_type::number:
      return "FLOAT";
    default:
      return "TEXT";
  }
}

// A default as help shows it: numbers in six significant digits (0.001, not 0.00100000005).
std::string help_text(const option_spec& spec, const std::string& value) {
  if (spec.type != option_type::number) return value;
  char text[32];
  std::snprintf(text, sizeof text, "%g", std::strtod(value.c_str(), nullptr));
  return text;
}

// Runs the entry's parser on the last value given; its kiln::error becomes CLI11's usage error
// ("--spp: expects an integer, got 'abc'").
CLI::callback_t apply(const option_spec& spec, render_options& options, bool deprecated) {
  return [&spec, &options, deprecated](const CLI::results_t& results) {
    if (results.empty()) return true;
    if (deprecated)
      std::cerr << "kiln: warning: --" << spec.alias << " is deprecated; use --" << spec.name << '\n';
    try {
      spec.set(options, results.back());
    } catch (const error& e) {
      throw CLI::ValidationError(e.location(), e.reason());
    }
    return true;
  };
}

void add_entry(CLI::App& app, const option_spec& spec, render_options& options) {
  std::string names = "--" + spec.name;
  if (!spec.short_name.empty()) names = "-" + spec.short_name + "," + names;
  for (bool deprecated : {false, true}) {
    if (deprecated && spec.alias.empty()) break;
    CLI::Option* option = app.add_option(deprecated ? "--" + spec.alias : names,
                                         apply(spec, options, deprecated), deprecated ? "" : spec.help);
    option->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    // Under its group's heading; a deprecated name is accepted, not offered.
    option->group(deprecated ? "" : option_group_title(spec.group));
    if (spec.type == option_type::flag) {
      option->expected(0, 1)->expected(0);  // a flag: --name, or --name=false in a manifest
      continue;
    }
    option->type_name(type_name(spec))->expected(1);
    if (const std::optional<std::string> value = spec.get(options))
      if (!value->empty()) option->default_str(help_text(spec, *value));
  }
}

// Options that were view options once: accepted with any value and never offered. The warning is
// given once a process (a batch parses each manifest job's options).
void add_retired_options(CLI::App& app, std::initializer_list<option_scope> scopes) {
  if (std::find(scopes.begin(), scopes.end(), option_scope::view) == scopes.end()) return;
  static std::set<std::string> warned;
  for (const retired_option& retired : retired_options()) {
    const std::string name = "--" + retired.name;
    app.add_option(
           name,
           [&retired, name](const CLI::results_t&) {
             if (warned.insert(name).second)
               std::cerr << "kiln: " << retired_option_warning(retired, name) << '\n';
             return true;
           },
           "")
        ->expected(1)
        ->group("");
  }
}

}  // namespace

void add_table_options(CLI::App& app, render_options& options, std::initializer_list<option_scope> scopes) {
  // CLI11 shows groups in the order their first option was added: group by group, in table order inside.
  for (option_group group : option_groups())
    for (const option_spec& spec : render_option_table())
      if (spec.group == group && std::find(scopes.begin(), scopes.end(), spec.scope) != scopes.end())
        add_entry(app, spec, options);
  add_retired_options(app, scopes);
}

}  // namespace kiln
