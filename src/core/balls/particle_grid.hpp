#pragma once
// The spatial hash grid that finds which balls touch (the idea of Mueller's "Ten Minute Physics"
// hashing lesson): cells as wide as the largest ball, each cell's integer coordinates hashed into
// a table of twice as many buckets as balls, and the balls counted into their buckets, so that a
// bucket's balls lie contiguously (a counting sort: no allocation per cell, no pointers). A ball
// meets only balls in the 27 cells around its own. Private to the core.
//
// Every ball's candidates are found independently (on all cores) and kept in index order, and the
// pairs listed ball by ball: the list, and so every result, is the same on any thread count.
// A few balls far larger than the rest stay out of the grid and are tested against every ball.
// Cells are at least a millionth of the balls' span wide, so that balls far smaller than their
// spread (1e-30 m apart by metres) do not all fall into the few cells at the hash's limit.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "parallel.hpp"
#include "pba/math.hpp"
#include "balls/spatial_hash.hpp"

namespace pba::detail {

class ParticleGrid {
public:
    /// Every pair (i < j) of balls closer than the sum of their radii, in the order of i, then j.
    /// x(i) is ball i's centre, radius(i) its radius (all radii at most maxRadius).
    template <class X, class R>
    void findPairs(std::size_t n, X&& x, R&& radius, double maxRadius,
                   std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs)
    {
        pairs.clear();
        if (n < 2 || !(maxRadius > 0.0))
            return;
        m_spacing = std::max(2.0 * setBigBallsAside(n, radius, maxRadius), span(n, x) / kMostCells);
        build(n, x);
        m_near.resize(n);
        forEachIndex(n, [&](std::size_t i) { nearOne(i, x, radius); });
        for (std::size_t i = 0; i < n; ++i)
            for (const std::uint32_t j : m_near[i])
                pairs.emplace_back(std::uint32_t(i), j);
    }

    /// The grid of n balls alone, for near().
    template <class X, class R>
    void build(std::size_t n, X&& x, R&& radius, double maxRadius)
    {
        m_spacing = std::max(2.0 * setBigBallsAside(n, radius, maxRadius), span(n, x) / kMostCells);
        build(n, x);
    }

    /// The balls of the grid that a ball of radius r at p touches, in index order, into out.
    template <class X, class R>
    void near(const dvec3& p, double r, X&& x, R&& radius, std::vector<std::uint32_t>& out) const
    {
        out.clear();
        const auto test = [&](std::uint32_t j) {
            const double reach = r + radius(j);
            const dvec3 d = x(j) - p;
            if (glm::dot(d, d) < reach * reach)
                out.push_back(j);
        };
        // A ball of the grid is within half a cell (its largest radius) of its cell.
        const auto cells = std::int64_t(std::ceil((r + 0.5 * m_spacing) / m_spacing));
        if (const auto side = 2 * cells + 1; side * side * side >= std::int64_t(m_mask) + 1) {
            for (std::uint32_t j = 0; j < m_radius.size(); ++j) // (a ball wider than the grid's buckets)
                test(j);
            return;
        }
        visitAround(p, cells, test);
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
    }

private:
    static constexpr double kMostCells = double(1 << 20); ///< across the balls' span
    static constexpr double kBig = 4.0;                   ///< times the median radius: a big ball
    static constexpr std::size_t kMostBig = 64;

    /// The largest extent of the balls' centres along an axis (the big ones' too).
    template <class X>
    static double span(std::size_t n, X& x)
    {
        dvec3 lo = x(0), hi = lo;
        for (std::size_t i = 1; i < n; ++i) {
            const dvec3 p = x(i);
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        const dvec3 extent = hi - lo;
        return std::max({extent.x, extent.y, extent.z});
    }

    /// A ball more than kBig times the median radius is tested against every ball rather than
    /// widening every cell: one 1 m ball beside a cloth of 1 cm balls put the whole cloth in a
    /// few cells. Up to kMostBig of them; more, and the cells are as wide as the largest ball.
    /// Returns the largest radius among the balls in the grid. The radii rarely change between
    /// steps: the split is kept while they and maxRadius stay as they were.
    template <class R>
    double setBigBallsAside(std::size_t n, R& radius, double maxRadius)
    {
        bool same = m_radius.size() == n && m_splitFor == maxRadius;
        m_radius.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const double r = radius(i);
            same = same && m_radius[i] == r;
            m_radius[i] = r;
        }
        if (same)
            return m_largest;
        m_splitFor = maxRadius;
        m_largest = splitByRadius(n, maxRadius);
        return m_largest;
    }

    double splitByRadius(std::size_t n, double maxRadius)
    {
        m_sorted.assign(m_radius.begin(), m_radius.end());
        std::nth_element(m_sorted.begin(), m_sorted.begin() + std::ptrdiff_t(n / 2), m_sorted.end());
        const double limit = kBig * m_sorted[n / 2];
        m_big.clear();
        m_isBig.assign(n, 0);
        double largest = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            if (m_radius[i] > limit) {
                m_big.push_back(std::uint32_t(i));
                m_isBig[i] = 1;
            } else {
                largest = std::max(largest, m_radius[i]);
            }
        }
        if (!m_big.empty() && (m_big.size() > kMostBig || !(largest > 0.0))) {
            m_big.clear();
            m_isBig.assign(n, 0);
            return maxRadius;
        }
        return largest;
    }

    template <class X>
    void build(std::size_t n, X& x)
    {
        // A power of two at least twice the balls: a bucket is a mask of the hash, where a
        // remainder was a 64-bit division for each of a ball's 27 cells.
        const std::uint32_t buckets = bucketsFor(2 * n);
        m_mask = buckets - 1;
        m_start.assign(buckets + 1, 0); // one more: bucket b's balls are m_entries[m_start[b], m_start[b + 1])
        m_bucket.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            if (m_isBig[i])
                continue;
            m_bucket[i] = bucketOf(cellOf(x(i), m_spacing), m_mask);
            ++m_start[m_bucket[i] + 1];
        }
        for (std::uint32_t b = 0; b < buckets; ++b)
            m_start[b + 1] += m_start[b];
        m_entries.resize(n - m_big.size());
        std::vector<std::uint32_t> fill(m_start.begin(), m_start.end() - 1);
        for (std::size_t i = 0; i < n; ++i)
            if (!m_isBig[i])
                m_entries[fill[m_bucket[i]]++] = std::uint32_t(i);
    }

    template <class X, class R>
    void nearOne(std::size_t i, X& x, R& radius)
    {
        std::vector<std::uint32_t>& near = m_near[i];
        near.clear();
        const dvec3 p = x(i);
        const auto test = [&](std::uint32_t j) {
            const double reach = radius(i) + radius(j);
            const dvec3 d = x(j) - p;
            if (j > i && glm::dot(d, d) < reach * reach)
                near.push_back(j);
        };
        if (m_isBig[i]) { // every ball after it
            for (std::size_t j = i + 1; j < m_isBig.size(); ++j)
                test(std::uint32_t(j));
            return;
        }
        visitAround(p, 1, test);
        // Two of the 27 cells may share a bucket: each ball once, in index order.
        std::sort(near.begin(), near.end());
        near.erase(std::unique(near.begin(), near.end()), near.end());
    }

    /// test(j) for each ball in the cells within `cells` of p's, and for each big ball (a ball
    /// may come twice: two cells may share a bucket).
    template <class Test>
    void visitAround(const dvec3& p, std::int64_t cells, Test& test) const
    {
        const GridCell c = cellOf(p, m_spacing);
        for (std::int64_t dx = -cells; dx <= cells; ++dx)
            for (std::int64_t dy = -cells; dy <= cells; ++dy)
                for (std::int64_t dz = -cells; dz <= cells; ++dz) {
                    const std::uint32_t b = bucketOf({c.x + dx, c.y + dy, c.z + dz}, m_mask);
                    for (std::size_t e = m_start[b]; e < m_start[b + 1]; ++e)
                        test(m_entries[e]);
                }
        for (const std::uint32_t j : m_big)
            test(j);
    }

    double m_spacing = 1.0;
    std::uint32_t m_mask = 0;
    std::vector<std::size_t> m_start;
    std::vector<std::uint32_t> m_bucket, m_entries;
    std::vector<std::vector<std::uint32_t>> m_near;
    std::vector<double> m_radius, m_sorted;
    double m_splitFor = -1.0; ///< the maxRadius the split below was made for
    double m_largest = 0.0;   ///< the largest radius in the grid, of that split
    std::vector<std::uint32_t> m_big;   ///< the balls tested against every ball, in index order
    std::vector<std::uint8_t> m_isBig;
};

} // namespace pba::detail
