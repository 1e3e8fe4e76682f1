// `kiln help`: kiln's --help, and, hidden from it, the man page, docs/options.md and the shell
// completion scripts written from the parsers of every command (`kiln help --man`, `--markdown`,
// `--bash-completion`, `--zsh-completion`), which the build and tools/make_options_doc.py run.
#pragma once

namespace CLI {
class App;
}

namespace kiln {

enum class help_format { usage, man, markdown, bash, zsh };

// Declares help's flags on command, writing the format chosen into format.
void add_help_options(CLI::App& command, help_format& format);

// Prints format to stdout for app, the whole command line with its subcommands.
void run_help(const CLI::App& app, help_format format);

}  // namespace kiln
