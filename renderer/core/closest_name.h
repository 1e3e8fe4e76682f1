// The known name a mistyped one was probably meant to be, by edit distance: "did you mean" in the
// command line's messages (kiln rendr -> render, --widht -> --width) and in --only/--holdout's
// (a node name). Depends on the standard library only.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace kiln {

// Optimal string alignment distance (Damerau-Levenshtein where each substring is edited once):
// insertions, deletions, substitutions and transpositions of neighbours each cost 1.
inline size_t edit_distance(const std::string& a, const std::string& b) {
  // d[i][j]: distance between the first i characters of a and the first j of b.
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// The candidate closest to word when it is close enough to be a typo: at most 2 edits, and fewer
// than half of word's characters (so "-x" suggests nothing). Ties go to the earlier candidate.
inline std::optional<std::string> closest_name(const std::string& word,
                                               const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  size_t best_distance = 3;  // the first distance too far
  for (const std::string& candidate : candidates) {
    const size_t distance = edit_distance(word, candidate);
    if (distance < best_distance && 2 * distance < word.size()) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

}  // namespace kiln
