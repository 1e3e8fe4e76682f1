// Messages for mistyped command lines: the closest known subcommand or option to an unknown one
// ("kiln rendr" -> render, "--widht" -> --width), by edit distance. App layer only.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace kiln {

// Optimal string alignment distance (Damerau-Levenshtein where each substring is edited once):
// insertions, deletions, substitutions and transpositions of neighbours each cost 1.
size_t edit_distance(const std::string& a, const std::string& b);

// The candidate closest to word when it is close enough to be a typo: at most 2 edits, and fewer
// than half of word's characters (so "-x" suggests nothing). Ties go to the earlier candidate.
std::optional<std::string> closest_name(const std::string& word, const std::vector<std::string>& candidates);

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
