#pragma once
// The pairs of balls near enough to touch, for the watches that measure overlaps after a run's
// steps (not the engine's contacts, which find their own): a grid of cells at least as wide as the
// largest ball and the reach, its cells sorted by their keys.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "pba/math.hpp"

namespace pba::study {

/// Calls visit(i, j) (i < j, each pair once) for each pair of `centres` (radii `radii`) whose
/// surfaces are less than `reach` apart. The cells are counted from the balls' lowest corner and
/// at least a millionth of their span wide, so any sizes and places fit the keys; a few balls
/// more than four times the median radius are tested against every ball instead of widening
/// every cell (as the engine's grid does).
template <class Visit>
void forNearPairs(const std::vector<dvec3>& centres, const std::vector<double>& radii, double reach, Visit&& visit)
{
    const std::size_t n = centres.size();
    if (n < 2)
        return;
    const auto near = [&](std::size_t i, std::size_t j) {
        return glm::length(centres[j] - centres[i]) < radii[i] + radii[j] + reach;
    };
    std::vector<double> sorted = radii;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(n / 2), sorted.end());
    std::vector<std::uint8_t> big(n, 0);
    std::size_t bigCount = 0;
    double largest = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        if (radii[i] > 4.0 * sorted[n / 2])
            big[i] = 1, ++bigCount;
        else
            largest = std::max(largest, radii[i]);
    if (bigCount > 64) {
        std::fill(big.begin(), big.end(), 0);
        largest = *std::max_element(radii.begin(), radii.end());
    }
    for (std::size_t i = 0; i < n; ++i) // the big ones against every ball
        if (big[i])
            for (std::size_t j = 0; j < n; ++j)
                if (j != i && (!big[j] || j > i) && near(i, j))
                    visit(std::min(i, j), std::max(i, j));
    dvec3 lo = centres[0], hi = centres[0];
    for (const dvec3& x : centres)
        lo = glm::min(lo, x), hi = glm::max(hi, x);
    const double span = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    constexpr double kCells = double(1 << 20);
    const double cell = std::max(2.0 * largest + reach, span / kCells);
    if (!(cell > 0.0)) { // every ball a point at one place
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i + 1; j < n; ++j)
                if (!big[i] && !big[j] && near(i, j))
                    visit(i, j);
        return;
    }
    const auto key = [&](const dvec3& x, int dx, int dy, int dz) {
        const auto c = [&](double v, double low, int d) {
            return std::uint64_t(std::int64_t(std::floor((v - low) / cell)) + 1 + d);
        };
        return (c(x.x, lo.x, dx) << 42) | (c(x.y, lo.y, dy) << 21) | c(x.z, lo.z, dz);
    };
    std::vector<std::pair<std::uint64_t, std::size_t>> cells;
    for (std::size_t i = 0; i < n; ++i)
        if (!big[i])
            cells.emplace_back(key(centres[i], 0, 0, 0), i);
    std::sort(cells.begin(), cells.end());
    for (const auto& [own, i] : cells)
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const std::uint64_t k = key(centres[i], dx, dy, dz);
                    auto it = std::lower_bound(cells.begin(), cells.end(), std::pair(k, std::size_t(0)));
                    for (; it != cells.end() && it->first == k; ++it)
                        if (const std::size_t j = it->second; j > i && near(i, j))
                            visit(i, j);
                }
}

} // namespace pba::study
