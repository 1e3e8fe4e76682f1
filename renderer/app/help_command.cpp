#include "app/help_command.h"

#include <CLI/CLI.hpp>
#include <iostream>

#include "app/man_page.h"
#include "app/options_markdown.h"
#include "app/shell_completion.h"

namespace kiln {

void add_help_options(CLI::App& command, help_format& format) {
  command.add_flag_callback(
      "--man", [&format] { format = help_format::man; }, "Print the man page (groff)");
  command.add_flag_callback(
      "--markdown", [&format] { format = help_format::markdown; }, "Print docs/options.md (Markdown)");
  command.add_flag_callback(
      "--bash-completion", [&format] { format = help_format::bash; }, "Print the bash completion script");
  command.add_flag_callback(
      "--zsh-completion", [&format] { format = help_format::zsh; }, "Print the zsh completion function");
}

void run_help(const CLI::App& app, help_format format) {
  switch (format) {
    case help_format::usage:
      std::cout << app.help();
      return;
    case help_format::man:
      return write_man_page(std::cout, app.get_description(), describe_commands(app));
    case help_format::markdown:
      return write_options_markdown(std::cout, app.get_description(), describe_commands(app));
    case help_format::bash:
      return write_bash_completion(std::cout, describe_commands(app));
    case help_format::zsh:
      return write_zsh_completion(std::cout, describe_commands(app));
  }
}

}  // namespace kiln
