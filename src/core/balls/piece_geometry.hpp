#pragma once
// The shape of a net's piece (a segment of two balls, or a triangle of three), as both the balls
// (net_pieces.hpp) and the rigid bodies (rigid/piece_contacts.hpp) meet it: one rule for how
// thick it is and for where a point lies on it. Private to the core.
#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "pba/math.hpp"

namespace pba::detail {

/// Nearer a piece's side or end than this share of it, a point is that side's or that ball's
/// own contact, not the piece's.
inline constexpr double kPieceEdge = 0.005;

/// A piece lies deeper in what it meets than its balls do only beyond this (m): level with its
/// balls to within rounding, it is lying along a surface, and its balls' own contacts hold it.
inline constexpr double kPieceLevel = 1e-7;

/// How thick a piece of balls at x (radii r) may be at most: half the smallest gap between two of
/// them (where two nearly touch, what lies in the groove rests on them, as it would without the
/// piece); 0 where two touch, leaving no inside.
inline double thickestPiece(std::span<const dvec3> x, std::span<const double> r)
{
    double thickest = INFINITY;
    const std::size_t count = x.size(), gaps = count == 2 ? 1 : count;
    for (std::size_t e = 0; e < gaps; ++e) {
        const std::size_t f = (e + 1) % count;
        const double gap = glm::length(x[f] - x[e]) - r[e] - r[f];
        if (!(gap > 0.0))
            return 0.0;
        thickest = std::min(thickest, 0.5 * gap);
    }
    return thickest;
}

/// Where the foot of p lies on the piece at x: on a segment's line or a triangle's plane, as
/// weights on its balls summing to 1 (a triangle's third weight 0 for a segment). False where
/// the triangle has no area or the foot lies within kPieceEdge of a side or an end, or outside.
inline bool footOnPiece(const dvec3& p, std::span<const dvec3> x, std::array<double, 3>& w)
{
    if (x.size() == 2) {
        const dvec3 d = x[1] - x[0];
        const double t = glm::dot(p - x[0], d) / glm::dot(d, d);
        w = {1.0 - t, t, 0.0};
    } else {
        const dvec3 e1 = x[1] - x[0], e2 = x[2] - x[0], q = p - x[0];
        const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
        const double det = d11 * d22 - d12 * d12;
        if (!(det > 0.0))
            return false;
        const double u = (d22 * glm::dot(q, e1) - d12 * glm::dot(q, e2)) / det;
        const double v = (d11 * glm::dot(q, e2) - d12 * glm::dot(q, e1)) / det;
        w = {1.0 - u - v, u, v};
    }
    for (std::size_t e = 0; e < x.size(); ++e)
        if (!(w[e] > kPieceEdge))
            return false;
    return true;
}

} // namespace pba::detail
