// kiln.1: the man page, written from the commands' own parsers (app/cli_reference.h) so it lists
// every option with its --help text, render's options one subsection per group. The build runs
// `kiln help --man` to make it; `cmake --install` puts it in share/man/man1.
#pragma once

#include <ostream>
#include <vector>

#include "app/cli_reference.h"

namespace kiln {

// The page in groff man macros; summary is the program's one-line description.
void write_man_page(std::ostream& out, const std::string& summary,
                    const std::vector<cli_command_reference>& commands);

}  // namespace kiln
