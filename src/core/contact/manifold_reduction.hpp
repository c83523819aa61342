#pragma once
// One rule for cutting a contact's candidate points down to a manifold's four, for every pair of
// shapes and for the room's surfaces alike (Box2D's and Jolt's reduction): the deepest, the one
// furthest from it, the one that makes the largest triangle with those two, and the one that adds
// the most area outside that triangle. Distances and areas are measured in the contact plane, so
// points that differ only in depth count as one place.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>

#include "manifold.hpp"

namespace pba::contact {

/// Twice the signed area of the triangle pqr seen along `normal`.
inline double areaAlong(const dvec3& p, const dvec3& q, const dvec3& r, const dvec3& normal)
{
    return glm::dot(normal, glm::cross(q - p, r - p));
}

/// Keeps at most Manifold::kMaxPoints of `points` in place (each with a `separation`, and a
/// place given by `position(point)`), by the rule above; the first of equals wins, so the result
/// depends on the order given only through ties. Returns how many are kept: fewer than four
/// when the points are all in one place, on one line or in one triangle.
template <class Point, class Position>
int reduceManifold(std::span<Point> points, const dvec3& normal, Position position)
{
    const std::size_t n = points.size();
    if (n <= static_cast<std::size_t>(Manifold::kMaxPoints))
        return static_cast<int>(n);
    // The index with the largest score (the first on a tie), and that score.
    const auto best = [n](auto&& score) {
        std::size_t index = 0;
        double top = score(0);
        for (std::size_t i = 1; i < n; ++i)
            if (const double s = score(i); s > top) {
                top = s;
                index = i;
            }
        return std::pair{index, top};
    };
    const auto at = [&](std::size_t i) -> dvec3 { return position(points[i]); };
    const std::size_t first = best([&](std::size_t i) { return -points[i].separation; }).first;
    const dvec3 p1 = at(first);
    const auto [second, length2] = best([&](std::size_t i) {
        const dvec3 d = at(i) - p1;
        const dvec3 across = d - glm::dot(d, normal) * normal;
        return glm::dot(across, across);
    });
    const dvec3 p2 = at(second);
    const auto [third, area] = best([&](std::size_t i) { return std::abs(areaAlong(p1, p2, at(i), normal)); });
    const dvec3 p3 = at(third);
    // Turned counter-clockwise, a point beyond one of the triangle's edges makes a negative area
    // with it: the largest such is (twice) the area that point adds.
    const double sign = areaAlong(p1, p2, p3, normal) > 0.0 ? 1.0 : -1.0;
    const auto [fourth, added] = best([&](std::size_t i) {
        const dvec3 q = at(i);
        return -std::min({sign * areaAlong(p1, p2, q, normal), sign * areaAlong(p2, p3, q, normal),
                          sign * areaAlong(p3, p1, q, normal)});
    });
    const int count = length2 <= 0.0 ? 1 : area <= 0.0 ? 2 : added <= 0.0 ? 3 : 4;
    const std::array<Point, 4> chosen{points[first], points[second], points[third], points[fourth]};
    std::copy_n(chosen.begin(), count, points.begin());
    return count;
}

} // namespace pba::contact
