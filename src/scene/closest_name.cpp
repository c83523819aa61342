#include "closest_name.hpp"

#include <algorithm>

namespace pba::scene_detail {

std::size_t editDistance(std::string_view a, std::string_view b)
{
    // d[i][j]: distance between the first i characters of a and the first j of b.
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i)
        d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j)
        d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

std::optional<std::string> closestName(std::string_view word, const std::vector<std::string>& candidates)
{
    // Two edits turn "dt" into any two-letter key: short words allow one.
    const std::size_t allowed = std::clamp<std::size_t>(word.size() / 3, 1, 2);
    std::optional<std::string> best;
    std::size_t bestDistance = allowed + 1;
    bool tie = false;
    for (const auto& candidate : candidates) {
        // The distance is at least the difference in length: a key of a megabyte is no one's
        // typo, and is not compared letter by letter.
        const std::size_t gap = word.size() > candidate.size() ? word.size() - candidate.size()
                                                               : candidate.size() - word.size();
        if (gap > allowed)
            continue;
        const std::size_t distance = editDistance(word, candidate);
        if (distance < bestDistance) {
            best = candidate;
            bestDistance = distance;
            tie = false;
        } else if (distance == bestDistance && best && *best != candidate) {
            tie = true;
        }
    }
    return tie ? std::nullopt : best;
}

} // namespace pba::scene_detail
