#pragma once
// A pair of polyhedra that has hardly moved against each other since the narrow phase last ran on
// it carries that manifold over instead of running it again (Jolt's body-pair cache): each point
// stays where it was on both bodies, and its separation is measured anew along the normal, which
// turns with A. In a heap most pairs rest or roll together, and the narrow phase between boxes
// (every face and edge pair's axis, then a face clipped against a face) was a fifth of a step.
#include "contact/manifold.hpp"
#include "rigid/contact.hpp"

namespace pba::rigid {

/// The most (m) any point of B may have moved in A's frame for the manifold to be carried over.
/// A feature the narrow phase left out lay further than its margin, so it lies no nearer than
/// this within the carried one's: the speculative margin's warning shrinks by this at most.
constexpr double kCarryDistance = 0.002;

/// The pair's pose where the narrow phase found a manifold of normal `worldNormal` within `margin`.
PairPose pairPose(const contact::Transform& ta, const dquat& qa, const dvec3& xb, const dquat& qb,
                  const dvec3& worldNormal, double margin);

/// `to` takes `from`'s points at the poses `ta` and `tb`, those within `margin` of touching, when
/// B (reaching `radiusB` from its centre) has moved by at most kCarryDistance in A's frame since
/// `from` was found and `margin` is no larger than what it was found within. Returns whether it did.
bool carryManifold(const Contact& from, const contact::Transform& ta, const dquat& qa, const contact::Transform& tb,
                   const dquat& qb, double radiusB, double margin, Contact& to);

} // namespace pba::rigid
