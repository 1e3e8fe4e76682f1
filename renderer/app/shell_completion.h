// bash and zsh completion scripts for kiln, written from the commands' own parsers
// (app/cli_reference.h): subcommands, every option name, a choice option's values, files for
// the options naming one. The build runs `kiln help --bash-completion` and `--zsh-completion`.
#pragma once

#include <ostream>
#include <vector>

#include "app/cli_reference.h"

namespace kiln {

// A script for bash-completion's completions/ folder (or to source): defines _kiln, completes kiln.
void write_bash_completion(std::ostream& out, const std::vector<cli_command_reference>& commands);

// A zsh completion function, the file _kiln in a folder of $fpath.
void write_zsh_completion(std::ostream& out, const std::vector<cli_command_reference>& commands);

}  // namespace kiln
