#pragma once
// "did you mean ...?" suggestions for misspelt keys and values.
#include <string>
#include <string_view>
#include <vector>

namespace crowdlab {

/// Levenshtein edit distance (insert, delete, substitute each cost 1; Levenshtein 1966), case-insensitive.
int edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `word` when it is plausibly a typo of it (edit distance <= 2, or <= a third
/// of the word's length for long words), else "". Ties go to the earlier candidate.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

/// " (did you mean 'x'?)" when closest_match finds one, else " (expected one of: a, b, c)".
std::string suggestion_suffix(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace crowdlab
