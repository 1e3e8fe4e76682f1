// docs/options.md: every option of every command as Markdown tables, written from the commands' own
// parsers (app/cli_reference.h) like the man page, render's options one section per --help group.
// `kiln help --markdown` prints it; tools/make_options_doc.py writes the page and checks it is current.
#pragma once

#include <ostream>
#include <vector>

#include "app/cli_reference.h"

namespace kiln {

// The page in GitHub-flavoured Markdown; summary is the program's one-line description.
void write_options_markdown(std::ostream& out, const std::string& summary,
                            const std::vector<cli_command_reference>& commands);

}  // namespace kiln
