// The particles' grid finds exactly the pairs of balls that touch, in index order, whatever their
// sizes: checked against every pair, with balls of one size, with a few far larger ones (kept out
// of the grid and tested against every ball), and with many large ones (the grid's cells widened).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "particle_grid.hpp"

namespace pba::detail {
namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

Pairs everyPair(const std::vector<dvec3>& x, const std::vector<double>& r)
{
    Pairs pairs;
    for (std::uint32_t i = 0; i < x.size(); ++i)
        for (std::uint32_t j = i + 1; j < x.size(); ++j) {
            const dvec3 d = x[j] - x[i];
            if (glm::dot(d, d) < (r[i] + r[j]) * (r[i] + r[j]))
                pairs.emplace_back(i, j);
        }
    return pairs;
}

TEST(ParticleGrid, FindsEveryTouchingPairWhateverTheBallsSizes)
{
    for (const std::size_t bigOnes : {std::size_t(0), std::size_t(3), std::size_t(100)}) {
        std::vector<dvec3> x;
        std::vector<double> r;
        for (int i = 0; i < 1500; ++i) { // a jumble of small balls, 1 to 2 cm
            x.emplace_back(0.4 * std::sin(1.3 * i), 0.4 * std::sin(0.7 * i + 1.0), 0.4 * std::cos(2.1 * i));
            r.push_back(0.01 + 0.01 * std::abs(std::sin(5.0 * i)));
        }
        for (std::size_t k = 0; k < bigOnes; ++k) { // among them, balls of 10 to 30 cm
            const std::size_t i = (k * 37) % x.size();
            r[i] = 0.1 + 0.2 * std::abs(std::sin(double(k)));
        }
        double largest = 0.0;
        for (const double ri : r)
            largest = std::max(largest, ri);
        ParticleGrid grid;
        Pairs found;
        grid.findPairs(x.size(), [&](std::size_t i) { return x[i]; }, [&](std::size_t i) { return r[i]; }, largest,
                       found);
        EXPECT_EQ(found, everyPair(x, r)) << bigOnes << " big balls";
    }
}

} // namespace
} // namespace pba::detail
