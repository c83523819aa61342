#pragma once
// How far two rigid bodies reach into each other where they stand, by the contacts' own narrow
// phase: what a scene's loader asks of a body and a fixed one before the first step. And which
// balls are near each other, by the particles' contacts' own grid: what the watches measure.
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "pba/rigid_body.hpp"

namespace pba {

/// The depth (m) of the deepest contact point of `a` and `b` at their poses: 0 when they are
/// apart or only touch.
double overlapDepth(const RigidBody& a, const RigidBody& b);
/// The same for a ball of `radius` at `centre` (a particle with a radius) and `body`.
double overlapDepth(const RigidBody& body, const dvec3& centre, double radius);
/// The same for the edge of a rope or cloth between balls at a and b of radii ra and rb (a rod
/// as thick as they are, linearly between them, but no thicker than half the gap between
/// them), looked at in `pieces` between the two: 0 for balls that touch.
double overlapDepth(const RigidBody& body, const dvec3& a, double ra, const dvec3& b, double rb, int pieces);
/// Half the smallest gap between two of a triangle's balls at x of radii r (how thick its
/// inside may be); 0 where two touch.
double halfSmallestGap(const std::array<dvec3, 3>& x, const std::array<double, 3>& r);
/// The same for a cloth's triangle between balls at x of radii r (as thick as they are by where
/// a point lies among them, but no thicker than half the gap between two): how far the body's
/// point furthest through its plane (a corner, a sphere's nearest point) reaches into it over its
/// inside, within its thickness. 0 for balls that touch.
double overlapDepth(const RigidBody& body, const std::array<dvec3, 3>& x, const std::array<double, 3>& r);

/// Every pair (i < j) of balls (`centres`, `radii`) whose surfaces are less than `gap` apart,
/// overlapping ones included, in the order of i, then j.
std::vector<std::pair<std::uint32_t, std::uint32_t>> nearBallPairs(std::span<const dvec3> centres,
                                                                   std::span<const double> radii, double gap);
/// Every pair of a ball (`centres`, `radii`) and a sphere (`around`, `reach`: the bounds of a
/// rope's or cloth's pieces, say) that overlap, as (ball, sphere), in the order of the ball, then
/// the sphere.
std::vector<std::pair<std::uint32_t, std::uint32_t>> ballsInSpheres(std::span<const dvec3> centres,
                                                                    std::span<const double> radii,
                                                                    std::span<const dvec3> around,
                                                                    std::span<const double> reach);

} // namespace pba
