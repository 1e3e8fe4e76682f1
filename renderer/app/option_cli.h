// The option table (job/option_table.h) on a CLI11 parser: each entry of the chosen scopes
// becomes an option whose text goes through the entry's own parser, so the command line, a batch
// manifest and the Python module accept and refuse the same values with the same words.
#pragma once

#include <initializer_list>

#include "job/option_table.h"

namespace CLI {
class App;
}

namespace kiln {

// Declares every table option of scopes on app, writing into options (which must outlive the
// parse), group by group under the groups' headings. Help shows each option's current value in
// options as its default. A command adding its own options to a group does so before this.
void add_table_options(CLI::App& app, render_options& options, std::initializer_list<option_scope> scopes);

}  // namespace kiln
