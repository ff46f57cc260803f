#include "sylva/dsl/EditDistance.h"

#include <algorithm>

namespace sylva::dsl {

std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) {
        row[j] = j;
    }
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            std::size_t above = row[j];
            std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + cost});
            diagonal = above;
        }
    }
    return row[b.size()];
}

std::optional<std::string> closestMatch(std::string_view word,
                                        const std::vector<std::string>& candidates,
                                        std::size_t maxDistance) {
    std::optional<std::string> best;
    std::size_t bestDistance = maxDistance + 1;
    for (const std::string& candidate : candidates) {
        if (candidate == word) {
            continue;
        }
        std::size_t distance = editDistance(word, candidate);
        // A one-letter name is "close" to every other one-letter name; don't suggest those.
        if (distance < bestDistance && distance < std::max(word.size(), candidate.size())) {
            best = candidate;
            bestDistance = distance;
        }
    }
    return best;
}

}  // namespace sylva::dsl
