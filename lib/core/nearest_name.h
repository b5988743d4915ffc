// The nearest of some names to a misspelt one, for a hint: a config key, a command-line option,
// a Python keyword argument ("unknown option --pach; the nearest option is --patch").
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace skinslide {

/// Levenshtein distance: the fewest one-character insertions, deletions and substitutions.
std::size_t edit_distance(const std::string& a, const std::string& b);

/// The name of `names` nearest to `name` by edit_distance (the first of equals, in the order
/// given); empty when `names` is.
std::string nearest_name(const std::string& name, const std::vector<std::string>& names);

}  // namespace skinslide
