#include "app/cli_suggest.h"

#include <CLI/CLI.hpp>
#include <algorithm>

#include "job/option_table.h"

namespace kiln {

std::optional<std::string> unknown_command_message(const CLI::App& app,
                                                   const std::vector<std::string>& arguments) {
  if (arguments.empty() || arguments[0].empty() || arguments[0][0] == '-') return std::nullopt;
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(command->get_name());
  const std::string& word = arguments[0];
  if (std::find(names.begin(), names.end(), word) != names.end()) return std::nullopt;
  std::string message = "unknown command '" + word + "'";
  if (std::optional<std::string> near = closest_name(word, names))
    return message + "; did you mean '" + *near + "'?";
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
  return message + " (commands: " + list + ")";
}

std::optional<std::string> unknown_option_message(const CLI::App& command,
                                                  const std::vector<std::string>& arguments) {
  std::vector<std::string> known;
  for (const CLI::Option* option : command.get_options())
    for (const std::string& name : option->get_lnames()) known.push_back("--" + name);
  // Ties go to the earlier option of the table, as the Python module's suggestions do, whatever
  // order --help's groups show them in; the command's own options come after.
  const std::vector<option_spec>& table = render_option_table();
  auto rank = [&table](const std::string& name) {
    const option_spec* spec = find_render_option(name);
    return spec ? size_t(spec - table.data()) : table.size();
  };
  std::stable_sort(known.begin(), known.end(),
                   [&rank](const std::string& a, const std::string& b) { return rank(a) < rank(b); });
  for (const std::string& argument : arguments) {
    if (argument == "--") break;  // the rest are positionals
    if (argument.rfind("--", 0) != 0 || argument.size() < 3) continue;
    const std::string name = argument.substr(0, argument.find('='));
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    std::string message = "unknown option " + name;
    if (std::optional<std::string> near = closest_name(name, known))
      return message + "; did you mean " + *near + "?";
    return message;
  }
  return std::nullopt;
}

}  // namespace kiln
