#pragma once
// The pieces of ropes and cloths (their segments and triangles) against rigid bodies. Their
// balls meet the bodies through the contact solve; what lies between two balls that a spring
// joins does not, so a box's edge under a sheet draped over it shows between two rows of balls,
// and a thin bar slips between a rope's.
// After the solve, each segment near a body is held out of it as a rod as thick as its balls
// (but no thicker than half the gap between them), at its one point nearest the body where it
// lies deeper than the straight line of its two balls' own separations (the shapes are convex:
// the separation along a segment has a single least), or at both ends of a stretch lying across a
// face. A cloth's triangles (three balls each two of which a segment joins) are held out of it
// too, at the body's point furthest through the triangle over its inside (a box's corner under a
// cell's middle), where that lies deeper than its balls. An impulse there goes to each ball by
// where the point lies among them, as to a point of a piece without mass, and back on the body.
// Private to the core.
#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "contact/narrow_phase.hpp"
#include "rigid/solver_body.hpp"

namespace pba::rigid {

/// A segment of a net: two point bodies (system indices) a spring joins, with no third ball of
/// the net between them.
struct Segment {
    std::uint32_t a = 0, b = 0;
};

/// Where a segment comes nearest a shape, deeper than its balls' straight line.
struct SegmentDepth {
    double t = 0.0;          ///< along the segment from its first ball, strictly inside (0, 1)
    dvec3 normal{0.0};       ///< world, from the shape towards the segment
    dvec3 point{0.0};        ///< on the segment's axis, world
    double separation = 0.0; ///< of the capsule there: below zero, an overlap
    double line = 0.0;       ///< what the two balls' separations give there, on their straight line
};

/// Where a segment touches a shape: at its deepest point, or at both ends of a stretch along
/// which it is as deep, as a segment lying across a face is.
struct SegmentDepths {
    int count = 0;
    std::array<SegmentDepth, 2> points{};
};

/// The segment from pa to pb, of radii ra and rb (linear between them, but no more than half
/// the gap between its balls), against `shape` at `pose`: where it comes within `margin` of the
/// shape and lies deeper than its balls' straight line (a segment lying along a face, as its
/// balls do, has no such point).
SegmentDepths deepestBetweenBalls(const contact::CollisionShape& shape, const contact::Transform& pose,
                                  const dvec3& pa, double ra, const dvec3& pb, double rb, double margin);

/// Where a cloth's triangle of three balls meets a shape: the shape's point furthest through the
/// triangle's plane towards it (a corner of a box, a sphere's nearest point) over the triangle's
/// inside, deeper than the triangle's balls' own separations there.
struct TriangleDepth {
    std::array<double, 3> weights{}; ///< the point's foot on the triangle, on its balls
    dvec3 normal{0.0};               ///< world, from the shape towards the triangle
    dvec3 point{0.0};                ///< the shape's point, world
    double separation = 0.0;         ///< of the triangle there, as thick as its balls: below zero, an overlap
    double line = 0.0;               ///< what the three balls' separations give there
};

/// The triangle of balls at x (radii r; as thick as they are by the weights, but no thicker than
/// half the gap between two of them) against `shape` at `pose`: where the shape comes within
/// `margin` of its inside, away from its sides (the segments hold those), deeper than its balls.
std::optional<TriangleDepth> deepestUnderTriangle(const contact::CollisionShape& shape, const contact::Transform& pose,
                                                  const std::array<dvec3, 3>& x, const std::array<double, 3>& r,
                                                  double margin);

/// A segment's or a triangle's contact with a body, at the end poses of the step.
struct PieceContact {
    /// The piece's balls: a segment's two (its third the second again, of weight 0), or a triangle's three.
    std::array<std::uint32_t, 3> ends{};
    std::array<double, 3> weights{}; ///< the point's, on its ends
    std::uint32_t body = 0;
    dvec3 normal{0.0}; ///< from the body towards the segment
    dvec3 arm{0.0};    ///< from the body's centre of mass at the end to the point
    /// How far to push the segment out along the normal: its overlap less its balls' line's.
    double depth = 0.0;
    /// How far it may still come towards the body in the step: its separation, if positive.
    double gap = 0.0;
    double friction = 0.0, restitution = 0.0;
};

/// Sweeps over the contacts: each takes the approach of its point away (rebounding by its
/// restitution when it arrives faster than `restingSpeed`), with Coulomb friction, on the end
/// velocities and by their drift over the step `dt` on the end poses; then pushes what still
/// overlaps out on the end poses. The order is the list's.
void holdPieces(std::span<const PieceContact> contacts, std::span<SolverBody> bodies, double restingSpeed,
                  double dt, int sweeps);

} // namespace pba::rigid
