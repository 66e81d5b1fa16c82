#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vibscore {

// The candidate a mistyped word most likely meant: the nearest by edit distance, if it is near
// enough to be a typo (at most a third of the word's letters, and at least one, differ).
std::optional<std::string> closest_name(std::string_view word,
                                        const std::vector<std::string>& candidates);

}  // namespace vibscore
