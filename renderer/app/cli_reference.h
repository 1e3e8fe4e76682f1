// kiln's commands and options as plain data, read from the CLI11 parser that the option table
// (job/option_table.h) fills: what the man page and the shell completions are written from, so
// they list exactly the options the parser accepts, in --help's groups and order.
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace kiln {

struct cli_option_reference {
  std::vector<std::string> names;  // "-o", "--output"
  std::string value_name;          // as --help shows it ("INT", "embree|grid|adaptive-grid"); empty: a flag
  std::string default_value;       // what --help shows after the value's '=' ("zip"); empty: none shown
  std::string help;
  std::vector<std::string> choices;  // the values it takes, when a fixed set
  bool names_file = false;           // the value is a file or folder path
  bool required = false;             // every call gives it (render's -o)
};

struct cli_option_group {
  std::string title;  // "Output", ...; "Options" for a command's own ungrouped options
  std::vector<cli_option_reference> options;
};

struct cli_command_reference {
  std::string name;  // "render"
  std::string description;
  std::vector<std::string> positionals;  // "asset"
  std::vector<cli_option_group> groups;  // --help's order; hidden options and --help itself left out
};

// Every subcommand of app that --help lists, in its order.
std::vector<cli_command_reference> describe_commands(const CLI::App& app);

// The command of that name among commands, or null.
const cli_command_reference* find_command(const std::vector<cli_command_reference>& commands,
                                          const std::string& name);

// A command's options set beside render's: the ones of its own, and the titles of render's groups
// it shares at least one option of (which the man page and docs/options.md name rather than repeat).
struct cli_own_options {
  std::vector<cli_option_reference> own;
  std::vector<std::string> shared_groups;
};
cli_own_options own_options(const cli_command_reference& command, const cli_command_reference* render);

}  // namespace kiln
