// "Did you mean": the known names closest to a misspelt one, for error messages (models, NBRDF
// materials, commands, options).
#pragma once

#include <string>
#include <vector>

namespace brdfit {

// The optimal string alignment distance (Damerau 1964; Levenshtein 1966 with adjacent
// transpositions as one edit, no substring edited twice): insertions, deletions, substitutions
// and swaps of two neighbouring characters, each costing 1.
std::size_t EditDistance(const std::string& a, const std::string& b);

// The candidates at the least edit distance from `given`, if that distance is small for its
// length (at most 1 for names of up to 4 characters, 2 up to 8, 3 beyond), in their order; at
// most three. Empty when nothing is close: a suggestion far from the typo would mislead.
std::vector<std::string> ClosestNames(const std::string& given,
                                      const std::vector<std::string>& candidates);

// "did you mean X?" / "did you mean X or Y?" for ClosestNames, or "" when there is none.
std::string DidYouMean(const std::string& given, const std::vector<std::string>& candidates);
// The same as " (did you mean X?)", to follow the quoted name in a message, or "".
std::string SuggestionAfter(const std::string& given, const std::vector<std::string>& candidates);

}  // namespace brdfit
