#pragma once
// How two touching things' materials combine (docs/scenes.md, "Two bodies' materials"), one rule
// for every pair that meets: rigid bodies, a ball and a body, and balls of ropes, cloths and swarms.
#include <algorithm>
#include <cmath>

namespace pba::detail {

/// Box2D's: the geometric mean, so that equal frictions give that friction and a frictionless
/// side makes the contact frictionless.
inline double combinedFriction(double a, double b) { return std::sqrt(a * b); }

/// Box2D's: the larger restitution, so that a bouncy ball bounces off a dead box.
inline double combinedRestitution(double a, double b) { return std::max(a, b); }

} // namespace pba::detail
