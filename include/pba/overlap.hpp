#pragma once
// How far two rigid bodies reach into each other where they stand, by the contacts' own narrow
// phase: what a scene's loader asks of a body and a fixed one before the first step.
#include "pba/rigid_body.hpp"

namespace pba {

/// The depth (m) of the deepest contact point of `a` and `b` at their poses: 0 when they are
/// apart or only touch.
double overlapDepth(const RigidBody& a, const RigidBody& b);
/// The same for a ball of `radius` at `centre` (a particle with a radius) and `body`.
double overlapDepth(const RigidBody& body, const dvec3& centre, double radius);

} // namespace pba
