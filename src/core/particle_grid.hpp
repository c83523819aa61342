#pragma once
// The spatial hash grid that finds which balls touch (the idea of Mueller's "Ten Minute Physics"
// hashing lesson): cells as wide as the largest ball, each cell's integer coordinates hashed into
// a table of twice as many buckets as balls, and the balls counted into their buckets, so that a
// bucket's balls lie contiguously (a counting sort: no allocation per cell, no pointers). A ball
// meets only balls in the 27 cells around its own. Private to the core.
//
// Every ball's candidates are found independently (on all cores) and kept in index order, and the
// pairs listed ball by ball: the list, and so every result, is the same on any thread count.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "parallel.hpp"
#include "pba/math.hpp"

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
        m_spacing = 2.0 * maxRadius;
        build(n, x);
        m_near.resize(n);
        forEachIndex(n, [&](std::size_t i) { nearOne(i, x, radius); });
        for (std::size_t i = 0; i < n; ++i)
            for (const std::uint32_t j : m_near[i])
                pairs.emplace_back(std::uint32_t(i), j);
    }

private:
    struct Cell {
        std::int64_t x, y, z;
    };
    Cell cellOf(const dvec3& p) const
    {
        return {std::int64_t(std::floor(p.x / m_spacing)), std::int64_t(std::floor(p.y / m_spacing)),
                std::int64_t(std::floor(p.z / m_spacing))};
    }
    /// Large odd multipliers spread neighbouring cells over the table; XOR mixes the three.
    std::size_t bucketOf(const Cell& c) const
    {
        const std::uint64_t h = std::uint64_t(c.x) * 92837111u ^ std::uint64_t(c.y) * 689287499u ^
                                std::uint64_t(c.z) * 283923481u;
        return std::size_t(h & (m_buckets - 1));
    }

    template <class X>
    void build(std::size_t n, X& x)
    {
        // A power of two at least twice the balls: a bucket is a mask of the hash, where a
        // remainder was a 64-bit division for each of a ball's 27 cells.
        std::size_t buckets = 2;
        while (buckets < 2 * n)
            buckets <<= 1;
        m_buckets = buckets;
        m_start.assign(buckets + 1, 0); // one more: bucket b's balls are m_entries[m_start[b], m_start[b + 1])
        m_bucket.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            m_bucket[i] = std::uint32_t(bucketOf(cellOf(x(i))));
            ++m_start[m_bucket[i] + 1];
        }
        for (std::size_t b = 0; b < buckets; ++b)
            m_start[b + 1] += m_start[b];
        m_entries.resize(n);
        std::vector<std::uint32_t> fill(m_start.begin(), m_start.end() - 1);
        for (std::size_t i = 0; i < n; ++i)
            m_entries[fill[m_bucket[i]]++] = std::uint32_t(i);
    }

    template <class X, class R>
    void nearOne(std::size_t i, X& x, R& radius)
    {
        std::vector<std::uint32_t>& near = m_near[i];
        near.clear();
        const dvec3 p = x(i);
        const Cell c = cellOf(p);
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dz = -1; dz <= 1; ++dz) {
                    const std::size_t b = bucketOf({c.x + dx, c.y + dy, c.z + dz});
                    for (std::size_t e = m_start[b]; e < m_start[b + 1]; ++e) {
                        const std::uint32_t j = m_entries[e];
                        const double reach = radius(i) + radius(j);
                        const dvec3 d = x(j) - p;
                        if (j > i && glm::dot(d, d) < reach * reach)
                            near.push_back(j);
                    }
                }
        // Two of the 27 cells may share a bucket: each ball once, in index order.
        std::sort(near.begin(), near.end());
        near.erase(std::unique(near.begin(), near.end()), near.end());
    }

    double m_spacing = 1.0;
    std::size_t m_buckets = 1;
    std::vector<std::size_t> m_start;
    std::vector<std::uint32_t> m_bucket, m_entries;
    std::vector<std::vector<std::uint32_t>> m_near;
};

} // namespace pba::detail
