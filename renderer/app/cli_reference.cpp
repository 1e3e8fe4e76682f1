#include "app/cli_reference.h"

#include <CLI/CLI.hpp>

#include "job/option_table.h"

namespace kiln {

namespace {

// The values of a CLI11 IsMember check, which --help shows as TEXT:{a,b,c}.
std::vector<std::string> member_choices(const std::string& type_name) {
  std::vector<std::string> choices;
  const size_t open = type_name.find('{');
  const size_t close = type_name.find('}', open);
  if (open == std::string::npos || close == std::string::npos) return choices;
  std::string item;
  for (char c : type_name.substr(open + 1, close - open - 1)) {
    if (c != ',') {
      item += c;
      continue;
    }
    choices.push_back(item);
    item.clear();
  }
  choices.push_back(item);
  return choices;
}

cli_option_reference describe_option(const CLI::Option& option) {
  cli_option_reference o;
  for (const std::string& name : option.get_snames()) o.names.push_back("-" + name);
  for (const std::string& name : option.get_lnames()) o.names.push_back("--" + name);
  o.help = option.get_description();
  o.required = option.get_required();
  if (option.get_type_size() == 0) return o;  // a flag
  o.value_name = option.get_type_name();
  o.default_value = option.get_default_str();
  if (const option_spec* spec = find_render_option(option.get_lnames().front())) {
    o.choices = spec->choices;
    o.names_file = spec->names_file;
    return o;
  }
  // The commands' own options: a fixed set, or a path (--json, --out-dir, -o), or a number.
  o.choices = member_choices(o.value_name);
  o.names_file = o.choices.empty() && o.value_name.rfind("TEXT", 0) == 0;
  return o;
}

cli_command_reference describe_command(const CLI::App& command) {
  cli_command_reference c;
  c.name = command.get_name();
  c.description = command.get_description();
  for (const CLI::Option* option : command.get_options()) {
    if (!option->nonpositional()) c.positionals.push_back(option->get_name());
  }
  for (const std::string& title : command.get_groups()) {
    if (title.empty()) continue;  // hidden
    cli_option_group group{title, {}};
    for (const CLI::Option* option : command.get_options()) {
      if (option->get_group() != title || !option->nonpositional() || option == command.get_help_ptr())
        continue;
      group.options.push_back(describe_option(*option));
    }
    if (!group.options.empty()) c.groups.push_back(std::move(group));
  }
  return c;
}

bool has_option(const cli_command_reference& command, const cli_option_reference& option) {
  for (const cli_option_group& group : command.groups)
    for (const cli_option_reference& known : group.options)
      if (known.names == option.names && known.help == option.help) return true;
  return false;
}

}  // namespace

std::vector<cli_command_reference> describe_commands(const CLI::App& app) {
  std::vector<cli_command_reference> commands;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; }))
    if (!command->get_group().empty()) commands.push_back(describe_command(*command));
  return commands;
}

const cli_command_reference* find_command(const std::vector<cli_command_reference>& commands,
                                          const std::string& name) {
  for (const cli_command_reference& command : commands)
    if (command.name == name) return &command;
  return nullptr;
}

cli_own_options own_options(const cli_command_reference& command, const cli_command_reference* render) {
  cli_own_options options;
  for (const cli_option_group& group : command.groups) {
    bool shares = false;
    for (const cli_option_reference& option : group.options) {
      if (render && has_option(*render, option))
        shares = true;
      else
        options.own.push_back(option);
    }
    if (shares) options.shared_groups.push_back(group.title);
  }
  return options;
}

}  // namespace kiln
