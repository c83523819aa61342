// The particles' grid finds exactly the pairs of balls that touch, in index order, whatever their
// sizes: checked against every pair, with balls of one size, with a few far larger ones (kept out
// of the grid and tested against every ball), with many large ones (the grid's cells widened),
// with balls far smaller than their spread, and when one grid meets other radii the next time.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "balls/particle_grid.hpp"
#include "pba/overlap.hpp"

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

Pairs found(ParticleGrid& grid, const std::vector<dvec3>& x, const std::vector<double>& r)
{
    double largest = 0.0;
    for (const double ri : r)
        largest = std::max(largest, ri);
    Pairs pairs;
    grid.findPairs(x.size(), [&](std::size_t i) { return x[i]; }, [&](std::size_t i) { return r[i]; }, largest, pairs);
    return pairs;
}

TEST(ParticleGrid, BallsFarSmallerThanTheirSpreadStillMeet)
{
    // A nanometre apart over a metre: cells two radii wide would number 1e9 across, beyond the
    // hash's limit; cells of a millionth of the span keep them apart.
    std::vector<dvec3> x;
    for (int i = 0; i < 400; ++i) { // in pairs 1.5 nm apart, the pairs 5 cm apart
        const int k = i / 2;
        x.emplace_back(double(k % 20) / 20.0 + 1.5e-9 * (i % 2), double(k / 20) / 20.0, 0.0);
    }
    const std::vector<double> r(x.size(), 1e-9);
    ParticleGrid grid;
    const Pairs pairs = found(grid, x, r);
    EXPECT_EQ(pairs, everyPair(x, r));
    EXPECT_FALSE(pairs.empty());
}

TEST(ParticleGrid, ANewSetOfRadiiIsSplitAgain)
{
    // The split into grid balls and big ones is kept while the radii stay as they were.
    std::vector<dvec3> x;
    std::vector<double> r;
    for (int i = 0; i < 600; ++i) {
        x.emplace_back(0.3 * std::sin(1.3 * i), 0.3 * std::sin(0.7 * i + 1.0), 0.3 * std::cos(2.1 * i));
        r.push_back(0.01);
    }
    ParticleGrid grid;
    EXPECT_EQ(found(grid, x, r), everyPair(x, r));
    r[17] = r[300] = 0.2; // two big balls now
    EXPECT_EQ(found(grid, x, r), everyPair(x, r));
    r[17] = r[300] = 0.01;
    EXPECT_EQ(found(grid, x, r), everyPair(x, r));
}

TEST(NearBallPairs, AreThePairsWhoseSurfacesAreWithinTheGap)
{
    std::vector<dvec3> x;
    std::vector<double> r;
    for (int i = 0; i < 800; ++i) {
        x.emplace_back(0.5 * std::sin(1.7 * i), 0.5 * std::sin(0.3 * i + 2.0), 0.5 * std::cos(1.1 * i));
        r.push_back(0.005 + 0.005 * std::abs(std::cos(3.0 * i)));
    }
    const double gap = 0.01;
    Pairs expected;
    for (std::uint32_t i = 0; i < x.size(); ++i)
        for (std::uint32_t j = i + 1; j < x.size(); ++j)
            if (glm::length(x[j] - x[i]) < r[i] + r[j] + gap)
                expected.emplace_back(i, j);
    EXPECT_EQ(nearBallPairs(x, r, gap), expected);
    EXPECT_GT(expected.size(), everyPair(x, r).size()); // the gap counts
}

} // namespace
} // namespace pba::detail
