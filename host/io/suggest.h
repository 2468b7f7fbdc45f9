// "Did you mean": the known name nearest to a mistyped one, for error messages of the command
// line and the library (commands, options, sensor profiles, parameters).
#pragma once
#include <string>
#include <vector>

namespace lpir {

// The entry of `known` nearest to `typed` by edit distance (a letter inserted, deleted, replaced,
// or two neighbours swapped; letter case ignored), when that distance is small enough to be a
// typo: at most a third of the longer name's length, and at least 1. "" when none is that near.
// Ties go to the first in `known`.
std::string ClosestName(const std::string& typed, const std::vector<std::string>& known);

// " (did you mean X?)" for ClosestName's X; "" when it has none.
std::string DidYouMean(const std::string& typed, const std::vector<std::string>& known);

}  // namespace lpir
