#pragma once
// The swarm's batch surface tests: loops over a block's structure-of-arrays coordinates that
// tell which points are clear of every plane (and need no collision rule), which are beyond
// one, and the bounds of a block, each written so GCC vectorises it. Private to the core (see
// pba/collision.hpp); the rules they filter for are in collision_rules.hpp.
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>

#include "surfaces/axis_plane.hpp"
#include "surfaces/collision_rules.hpp"
#include "pba/collision.hpp"

namespace pba {

namespace collision_detail {

/// lowerClearance's loop for one form of the plane's geometry, taken by value so the stores
/// to margin cannot change it. For a wall (AxisPlaneT) the distance is one coordinate, and the
/// loop reads one array instead of three.
template <class Geometry, class T>
inline std::uint32_t lowerClearanceOf(const Geometry plane, T tolerance, const T* __restrict x,
                                      const T* __restrict y, const T* __restrict z, std::size_t n,
                                      T* __restrict margin)
{
    std::uint32_t beyond = 0; // 32 bits: a counter as wide as T keeps the loop in one vector width
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k) {
        const T d = plane.distance(Vec3<T>(x[k], y[k], z[k]));
        const T clearance = d - tolerance;
        margin[k] = clearance < margin[k] ? clearance : margin[k]; // not std::min: its reference stops the vectoriser
        beyond += static_cast<std::uint32_t>(d < T(0));
    }
    return beyond;
}

} // namespace collision_detail

/// Lowers margin[k] to the clearance of point k (SoA arrays, n of them) from `plane`: its
/// distance beyond the plane's contact tolerance, so a point is clear of every plane when its
/// smallest margin is positive. A step whose start and end are clear of every plane needs no
/// collision rule at all; the others get the full rule. Plane-major and in the scalar type
/// (three multiply-adds and a min a point, no conversion to flags per plane), so each loop is
/// a straight line of arithmetic that vectorises. (A path that leaves and re-enters within one
/// step, an apex beyond the ceiling, is not seen by this end-point test.) Returns how many of
/// the points are beyond the plane itself, which tells whether the plane's rule has work.
template <class T>
inline std::size_t lowerClearance(const PlaneT<T>& plane, const T* __restrict x, const T* __restrict y,
                                  const T* __restrict z, std::size_t n, T* __restrict margin)
{
    const T tolerance = collision_detail::contactTolerance(plane);
    return withPlaneGeometry(plane, [&](const auto geometry) {
        return collision_detail::lowerClearanceOf(geometry, tolerance, x, y, z, n, margin);
    });
}

/// The six walls of a box among a world's planes (a hole in one is allowed: the surface test
/// that uses this is only a filter), for testing many points against all six in one loop.
template <class T>
struct BoxWallsT {
    std::array<T, 3> lo, hi;           ///< a point is beyond none of the walls when lo <= x <= hi
    std::array<T, 3> clearLo, clearHi; ///< and clear of them (beyond the contact tolerance) between these
    std::array<int, 6> plane;          ///< the walls' indices in the span: low x, high x, low y, ...
    std::uint64_t mask = 0;            ///< bits of those indices (below 64)
};

/// The box whose walls are among `planes`, if every axis has a wall on each side.
template <class T>
inline std::optional<BoxWallsT<T>> boxWalls(std::span<const PlaneT<T>> planes)
{
    BoxWallsT<T> box;
    for (int axis = 0; axis < 3; ++axis) {
        const auto [low, high] = collision_detail::wallsOnAxis(planes, axis, true);
        if (low < 0 || high < 0 || low >= 64 || high >= 64)
            return std::nullopt;
        const PlaneT<T>& l = planes[std::size_t(low)];
        const PlaneT<T>& h = planes[std::size_t(high)];
        const auto i = std::size_t(axis);
        box.lo[i] = l.offset;
        box.hi[i] = -h.offset;
        box.clearLo[i] = l.offset + collision_detail::contactTolerance(l);
        box.clearHi[i] = -h.offset - collision_detail::contactTolerance(h);
        box.plane[2 * i] = low;
        box.plane[2 * i + 1] = high;
        box.mask |= std::uint64_t(1) << low | std::uint64_t(1) << high;
    }
    return box;
}

/// The region clear of the box's walls (beyond their contact tolerance), by value, so the loops
/// that hold one need no alias checks. `margin` is lowerClearance's margin for all six walls
/// (positive: clear).
template <class T>
struct ClearRegionT {
    T xl, xh, yl, yh, zl, zh;

    explicit ClearRegionT(const BoxWallsT<T>& box)
        : xl(box.clearLo[0]), xh(box.clearHi[0]), yl(box.clearLo[1]), yh(box.clearHi[1]), zl(box.clearLo[2]),
          zh(box.clearHi[2])
    {
    }
    T margin(T a, T b, T c) const
    {
        using collision_detail::lesser;
        return lesser(lesser(lesser(a - xl, xh - a), lesser(b - yl, yh - b)), lesser(c - zl, zh - c));
    }
};

/// lowerClearance for all six walls of a box in one loop: each coordinate is read once and the
/// margins written once, where six plane-by-plane loops read and wrote the margins six times
/// (this was a sixth of a swarm step). A point beyond a wall is never clear of it (x < lo
/// implies x < clearLo). Sets margin[k]; the other planes then lower it.
template <class T>
inline void setClearanceInBox(const BoxWallsT<T>& box, const T* __restrict x, const T* __restrict y,
                              const T* __restrict z, std::size_t n, T* __restrict margin)
{
    const ClearRegionT<T> region(box);
    for (std::size_t k = 0; k < n; ++k)
        margin[k] = region.margin(x[k], y[k], z[k]);
}

/// unclear[k] = 1 for the points not clear of the box's walls, 0 for the others; returns how many
/// there are. (Counting first and marking only when some are was measured slower: one pass
/// fewer where particles meet the walls outweighs the flags written for nothing in flight.)
/// The test is the margin's sign, not six comparisons joined by `and` (the same answer: with
/// gradual underflow x - lo > 0 exactly when x > lo, and a NaN the rule leaves as it is): the
/// comparisons become a chain of six masked compares, each waiting for the last, twice as slow
/// as five minima and one compare, a fifth of a swarm's step in flight.
template <class T>
inline std::uint32_t markUnclearInBox(const ClearRegionT<T> region, const T* __restrict x, const T* __restrict y,
                                      const T* __restrict z, std::size_t n, std::uint8_t* __restrict unclear)
{
    std::uint32_t count = 0; // 32 bits, as in lowerClearance
    for (std::size_t k = 0; k < n; ++k) {
        unclear[k] = static_cast<std::uint8_t>(!(region.margin(x[k], y[k], z[k]) > T(0)));
        count += unclear[k];
    }
    return count;
}

/// Whether x is clear of every plane (see lowerClearance).
template <class T>
inline bool clearOfAll(std::span<const PlaneT<T>> planes, const Vec3<T>& x)
{
    T margin = std::numeric_limits<T>::infinity();
    for (const PlaneT<T>& plane : planes)
        lowerClearance(plane, &x.x, &x.y, &x.z, 1, &margin);
    return margin > T(0);
}

} // namespace pba
