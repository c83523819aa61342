// The exact normal solve's quadratic program (src/core/rigid/bounded_qp.hpp) against hand-worked
// cases (bounds below and above) and against the small LCP's active sets, which it must agree with wherever both apply;
// and a chain of far unequal masses, whose conditioning is what sweeps cannot pass.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

#include "core/rigid/bounded_qp.hpp"
#include "core/rigid/small_lcp.hpp"

namespace {

using pba::rigid::QpProduct;
using pba::rigid::solveBoundedQp;

constexpr double kNone = std::numeric_limits<double>::infinity();

QpProduct denseProduct(const std::vector<double>& a, std::size_t n)
{
    return [&a, n](std::span<const double> in, std::span<double> out) {
        for (std::size_t i = 0; i < n; ++i) {
            out[i] = 0.0;
            for (std::size_t j = 0; j < n; ++j)
                out[i] += a[i * n + j] * in[j];
        }
    };
}

std::vector<double> solve(const std::vector<double>& a, const std::vector<double>& c, const std::vector<double>& lower,
                          std::vector<double> upper = {})
{
    const std::size_t n = c.size();
    upper.resize(n, kNone);
    const QpProduct multiply = denseProduct(a, n);
    std::vector<double> y(n);
    for (std::size_t i = 0; i < n; ++i)
        y[i] = std::max(lower[i], 0.0);
    const auto result =
        solveBoundedQp(multiply, c, lower, upper, pba::rigid::largestEigenvalue(multiply, n) * 1.1, 1e-12, 10000, y);
    EXPECT_LE(result.projectedGradient, 1e-12);
    return y;
}

TEST(BoundedQp, StopsAtTheBoundOrWhereTheSpeedIsZero)
{
    const std::vector<double> a{2.0, 1.0, 1.0, 2.0};
    // Both rows held: A y = -c.
    auto y = solve(a, {-3.0, -3.0}, {0.0, 0.0});
    EXPECT_NEAR(y[0], 1.0, 1e-10);
    EXPECT_NEAR(y[1], 1.0, 1e-10);
    // The second would pull: it stays at its bound, the first alone stops its speed.
    y = solve(a, {-4.0, 1.0}, {0.0, 0.0});
    EXPECT_NEAR(y[0], 2.0, 1e-10);
    EXPECT_EQ(y[1], 0.0);
    // A bound below zero (the change of an impulse that was 1): the row may give back all of it.
    y = solve({2.0}, {4.0}, {-1.0});
    EXPECT_EQ(y[0], -1.0);
    y = solve({2.0}, {1.0}, {-1.0});
    EXPECT_NEAR(y[0], -0.5, 1e-12);
    // An upper bound holds too, and the other row takes what the bounded one cannot.
    y = solve(a, {-4.0, -2.0}, {0.0, 0.0}, {1.0, kNone});
    EXPECT_EQ(y[0], 1.0);
    EXPECT_NEAR(y[1], 0.5, 1e-10);
}

TEST(BoundedQp, AgreesWithTheActiveSetsOnRandomPrograms)
{
    std::mt19937 random(7);
    std::normal_distribution<double> normal;
    for (int trial = 0; trial < 50; ++trial) {
        const std::size_t n = 2 + std::size_t(trial % 9), m = n + 3;
        // A = J J^T: positive definite, as a contact island's rows are when none is redundant.
        std::vector<double> j(n * m), a(n * n, 0.0), c(n);
        for (double& v : j)
            v = normal(random);
        for (std::size_t r = 0; r < n; ++r)
            for (std::size_t s = 0; s < n; ++s)
                for (std::size_t k = 0; k < m; ++k)
                    a[r * n + s] += j[r * m + k] * j[s * m + k];
        for (double& v : c)
            v = normal(random);
        std::vector<double> x;
        pba::rigid::solveSmallLcp(a, c, n, 1e-14, x);
        const auto y = solve(a, c, std::vector<double>(n, 0.0));
        for (std::size_t i = 0; i < n; ++i)
            EXPECT_NEAR(y[i], x[i], 1e-8) << "trial " << trial << ", row " << i;
    }
}

TEST(BoundedQp, AChainOfFarUnequalMassesIsSolvedInFewProducts)
{
    // A column of bodies on the floor, 0.1 and 50 kg in turn, each row the contact under a body:
    // row i's speed is v_i - v_{i-1}; an impulse on it pushes body i up and body i - 1 down.
    // Each row's speed must rise by g dt to hold the column: the exact impulses are the weights
    // above. Gauss-Seidel passes 1/500 of the load a sweep; the program's rows, scaled to unit
    // diagonal, take a few products per body.
    const std::size_t n = 12;
    std::vector<double> inverseMass(n);
    for (std::size_t i = 0; i < n; ++i)
        inverseMass[i] = i % 2 == 0 ? 10.0 : 0.02;
    const double push = 9.81 * 0.005;
    std::vector<double> a(n * n, 0.0), scale(n);
    for (std::size_t i = 0; i < n; ++i) {
        a[i * n + i] = inverseMass[i] + (i > 0 ? inverseMass[i - 1] : 0.0);
        if (i > 0)
            a[i * n + i - 1] = a[(i - 1) * n + i] = -inverseMass[i - 1];
    }
    for (std::size_t i = 0; i < n; ++i)
        scale[i] = 1.0 / std::sqrt(a[i * n + i]);
    std::vector<double> scaled(n * n), c(n);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = 0; k < n; ++k)
            scaled[i * n + k] = scale[i] * a[i * n + k] * scale[k];
        // Every body falls at g dt: the rows between two bodies are at rest, the floor's approaches.
        c[i] = scale[i] * (i == 0 ? -push : 0.0);
    }
    const QpProduct multiply = denseProduct(scaled, n);
    std::vector<double> y(n, 0.0);
    const auto result = solveBoundedQp(multiply, c, std::vector<double>(n, 0.0), std::vector<double>(n, kNone),
                                       1.1 * pba::rigid::largestEigenvalue(multiply, n), 1e-12, 200, y);
    EXPECT_LE(result.projectedGradient, 1e-12);
    EXPECT_LE(result.iterations, 4 * int(n));
    double above = 0.0;
    for (std::size_t i = n; i-- > 0;) {
        above += push / inverseMass[i];
        EXPECT_NEAR(scale[i] * y[i], above, 1e-9 * above) << "row " << i;
    }
}

} // namespace
