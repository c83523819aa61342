#pragma once
// The spatial hash that the grids of pba's contacts share (the broad phase's, the particles' and
// XPBD's around rigid bodies): a point's integer cell, and the cell hashed into a table of a
// power of two buckets (Teschner et al.'s hash, the primes of Mueller's "Ten Minute Physics").
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "pba/math.hpp"

namespace pba::detail {

struct GridCell {
    std::int64_t x = 0, y = 0, z = 0;
    friend bool operator==(const GridCell&, const GridCell&) = default;
};

/// A coordinate's cell, held within 2^31 cells of the origin: a body blowing up (which the step's
/// own checks report) may reach 1e19 m or NaN, which no integer holds, and the hash's products of
/// a held index cannot overflow.
inline std::int64_t cellIndex(double v, double cellSize)
{
    constexpr double kFar = 2147483648.0;
    const double c = std::floor(v / cellSize);
    return std::int64_t(c > -kFar ? (c < kFar ? c : kFar) : -kFar); // NaN too goes to -kFar
}

inline GridCell cellOf(const dvec3& p, double cellSize)
{
    return {cellIndex(p.x, cellSize), cellIndex(p.y, cellSize), cellIndex(p.z, cellSize)};
}

/// The cell's bucket in a table of mask + 1 buckets (a power of two): large odd multipliers
/// spread neighbouring cells over the table, XOR mixes the three.
inline std::uint32_t bucketOf(const GridCell& c, std::uint32_t mask)
{
    const std::uint64_t h = std::uint64_t(c.x * 92837111) ^ std::uint64_t(c.y * 689287499) ^ std::uint64_t(c.z * 283923481);
    return std::uint32_t(h) & mask;
}

/// The smallest power of two at least `atLeast`: a table's bucket count.
inline std::uint32_t bucketsFor(std::size_t atLeast)
{
    std::uint32_t buckets = 1;
    while (buckets < atLeast)
        buckets <<= 1;
    return buckets;
}

} // namespace pba::detail
