// Messages for mistyped command lines: the closest known subcommand or option to an unknown one
// ("kiln rendr" -> render, "--widht" -> --width), by edit distance. App layer only.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/closest_name.h"

namespace CLI {
class App;
}

namespace kiln {

// "unknown command 'rendr'; did you mean 'render'?" when arguments[0] names no subcommand of app;
// nothing when it does (or is an option).
std::optional<std::string> unknown_command_message(const CLI::App& app,
                                                   const std::vector<std::string>& arguments);

// "unknown option --widht; did you mean --width?" (or just "unknown option --xyz" when nothing is
// close) for the first long option of arguments that command does not declare; nothing when every
// option is known.
std::optional<std::string> unknown_option_message(const CLI::App& command,
                                                  const std::vector<std::string>& arguments);

}  // namespace kiln
