// The distance between two words, for "did you mean" on a misspelt name.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace tidepool::base {

/// Levenshtein distance: the fewest single-character insertions, deletions and substitutions
/// that turn `a` into `b`. Costs |a| times |b|: callers cut very long words first.
std::size_t EditDistance(std::string_view a, std::string_view b);

/// The name in `names` nearest to `word` by EditDistance (the first of equals); "" when `names`
/// is empty.
std::string ClosestName(std::string_view word, const std::vector<std::string>& names);

}  // namespace tidepool::base
