// The collision pass's small LCP (src/core/rigid/small_lcp.hpp) against hand-worked cases: both
// rows pushing, one left slack, and a redundant row (four points of one face on a body that
// turns three ways), where any split of the push that meets the speeds will do.
#include <gtest/gtest.h>

#include <vector>

#include "core/rigid/small_lcp.hpp"

namespace {

using pba::rigid::solveSmallLcp;

std::vector<double> speeds(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& x)
{
    const std::size_t n = b.size();
    std::vector<double> w(b);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
            w[i] += a[i * n + j] * x[j];
    return w;
}

TEST(SmallLcp, PushesWhereItMustAndNowhereElse)
{
    // Two coupled rows, both approaching: both push, each speed brought to 0.
    const std::vector<double> a{2.0, 1.0, 1.0, 2.0};
    std::vector<double> x;
    solveSmallLcp(a, {-3.0, -3.0}, 2, 1e-12, x);
    EXPECT_NEAR(x[0], 1.0, 1e-8);
    EXPECT_NEAR(x[1], 1.0, 1e-8);
    // The second row would pull (x < 0) to stop: it is left slack, separating.
    solveSmallLcp(a, {-4.0, 1.0}, 2, 1e-12, x);
    EXPECT_NEAR(x[0], 2.0, 1e-8);
    EXPECT_EQ(x[1], 0.0);
    EXPECT_NEAR(speeds(a, {-4.0, 1.0}, x)[1], 3.0, 1e-8);
    // Nothing approaching: no push at all.
    solveSmallLcp(a, {1.0, 0.5}, 2, 1e-12, x);
    EXPECT_EQ(x[0], 0.0);
    EXPECT_EQ(x[1], 0.0);
}

TEST(SmallLcp, ARedundantRowStillMeetsEverySpeed)
{
    // Rows 1 and 2 are the same row twice (A singular): their pushes share what one would take.
    const std::vector<double> a{2.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
    const std::vector<double> b{-2.0, -1.0, -1.0};
    std::vector<double> x;
    solveSmallLcp(a, b, 3, 1e-12, x);
    const std::vector<double> w = speeds(a, b, x);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_GE(x[i], 0.0);
        EXPECT_NEAR(w[i], 0.0, 1e-8) << i;
    }
}

} // namespace

namespace {

TEST(SmallLcp, AnEqualityRowPullsAsWellAsPushes)
{
    // Row 0 an equality (a joint's): its speed is brought to 0 even by a pull (x < 0); row 1,
    // a contact coupled to it, is left slack when it separates under that pull.
    const std::vector<double> a{2.0, 1.0, 1.0, 2.0};
    std::vector<double> x;
    solveSmallLcp(a, {4.0, 3.0}, 2, 1e-12, x, 1);
    EXPECT_NEAR(x[0], -2.0, 1e-8);
    EXPECT_EQ(x[1], 0.0);
    EXPECT_NEAR(speeds(a, {4.0, 3.0}, x)[1], 1.0, 1e-8);
    // The equality's pull brings the contact to approach (1 - 2 < 0): it pushes too, both speeds 0.
    solveSmallLcp(a, {4.0, 1.0}, 2, 1e-12, x, 1);
    EXPECT_NEAR(x[0], -7.0 / 3.0, 1e-8);
    EXPECT_NEAR(x[1], 2.0 / 3.0, 1e-8);
}

} // namespace
