#pragma once
// The checks that a World's phases share as they write the bodies' new states: whether a state
// is finite, which surface holds a rigid body's centre, and the lowest failing body of a
// parallel pass. Private to the world's files (src/core/world_*.cpp).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "pba/collision.hpp"
#include "pba/math.hpp"

namespace pba::detail {

/// The smallest index of a body, among `members`, for which `check(k)` (which may also store
/// member k's new state) reports false, on all cores in ranges of `grain`; `none` when it
/// reports true for every one. (Each body's work is its own: the answer does not depend on the
/// thread count.)
template <class Check>
std::size_t lowestFailing(const std::vector<std::size_t>& members, std::size_t grain, std::size_t none, Check&& check)
{
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, members.size(), grain), none,
        [&](const tbb::blocked_range<std::size_t>& r, std::size_t lowest) {
            for (std::size_t k = r.begin(); k < r.end(); ++k)
                if (!check(k))
                    lowest = std::min(lowest, members[k]);
            return lowest;
        },
        [](std::size_t a, std::size_t b) { return std::min(a, b); });
}

inline bool isFinite(const dvec3& u) { return std::isfinite(u.x) && std::isfinite(u.y) && std::isfinite(u.z); }

/// The first of `planes` that a rigid body's centre x lies on or beyond: at least half the body
/// inside the floor or a wall, since its centre of mass lies within the hull of its points. Not
/// the floor within `reach` (the body's bounding radius) of a hole's edge, where part of a body
/// hangs into the shaft. -1 if none.
inline int surfaceHolding(std::span<const Plane> planes, const dvec3& x, double reach)
{
    for (std::size_t p = 0; p < planes.size(); ++p) {
        const Plane& plane = planes[p];
        if (!(plane.distance(x) <= 0.0))
            continue;
        if (plane.holeRadius > 0.0 && glm::length(plane.fromHoleAxis(x)) < plane.holeRadius + reach)
            continue;
        return int(p);
    }
    return -1;
}

} // namespace pba::detail
