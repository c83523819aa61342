#pragma once
// Joints between two rigid bodies, or between a rigid body and the world: a ball (spherical)
// joint keeps two points together, a hinge also keeps an axis (and, with limits, an angle range),
// a distance joint keeps two points a length apart (rigidly, or as a spring), a fixed joint
// keeps the two bodies as they were. Anchors and axes are given in the world at the start; each
// body keeps them in its own frame from then on.
#include <array>
#include <optional>
#include <string_view>

#include "pba/math.hpp"

namespace pba {

enum class JointType { Ball, Hinge, Distance, Fixed };

/// "ball", "hinge", "distance", "fixed".
std::string_view jointTypeName(JointType type);
std::optional<JointType> jointTypeFromName(std::string_view name);

struct JointDesc {
    JointType type = JointType::Ball;
    std::size_t bodyA = 0;             ///< a rigid body's index in the world
    std::optional<std::size_t> bodyB;  ///< the other's, or none: the body is joined to the world
    dvec3 anchor{0.0};                 ///< ball, hinge, fixed: the joint's point, world frame
    std::array<dvec3, 2> anchors{};    ///< distance: the point on each body (on A, on B or the world)
    dvec3 axis{0.0, 1.0, 0.0};         ///< hinge: the axis, world frame (any length but zero)
    /// hinge: the range of the angle A turns about the axis relative to B (or the world),
    /// right-handed, radians, from the start's 0 (lower <= 0 <= upper).
    std::optional<std::array<double, 2>> limits;
    std::optional<double> length;      ///< distance: default, the anchors' distance at the start
    /// distance: a spring of this stiffness (N/m) and damping (N s/m) instead of a rigid rod.
    std::optional<double> stiffness;
    double damping = 0.0;
    /// Two bodies: whether they still collide with each other. Off, as in Box2D and Jolt: joined
    /// bodies usually touch or overlap at the joint (a hinge's links, a body welded into another),
    /// and a contact there would fight the joint.
    bool collide = false;
};

/// Where a joint is now, for drawing it: its point on each body (the same point while the joint
/// holds) and, for a hinge, its axis.
struct JointFrame {
    JointType type = JointType::Ball;
    std::size_t bodyA = 0;            ///< world index
    std::optional<std::size_t> bodyB; ///< world index; none when joined to the world
    dvec3 onA{0.0}, onB{0.0};
    dvec3 axis{0.0};
    double length = 0.0;    ///< a distance joint's
    double stiffness = 0.0; ///< a distance joint's: 0 for a rod
    double damping = 0.0;   ///< a spring-like distance joint's
};

} // namespace pba
