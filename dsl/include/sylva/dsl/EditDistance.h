// Levenshtein distance and "did you mean" lookup for names, kinds and attributes.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::dsl {

// Number of single-byte insertions, deletions and substitutions turning `a` into `b`.
std::size_t editDistance(std::string_view a, std::string_view b);

// The candidate closest to `word` within `maxDistance` (first one on ties); nullopt if none.
std::optional<std::string> closestMatch(std::string_view word,
                                        const std::vector<std::string>& candidates,
                                        std::size_t maxDistance = 2);

}  // namespace sylva::dsl
