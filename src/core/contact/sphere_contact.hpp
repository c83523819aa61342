#pragma once
// The manifolds with a sphere in them: one point each, on the line of least distance.
#include "convex_polyhedron.hpp"
#include "manifold.hpp"

namespace pba::contact {

/// Sphere A (radius `ra`) against sphere B: the normal along the centres, or +y when they
/// coincide. Count 0 when further apart than `margin`.
Manifold sphereSphere(double ra, const Transform& ta, double rb, const Transform& tb, double margin);

/// Polyhedron A against sphere B: the normal from A's point closest to B's centre towards it; a
/// centre inside A leaves through the face it is least deep below. Count 0 when further apart
/// than `margin`.
Manifold polyhedronSphere(const ConvexPolyhedron& a, const Transform& ta, double rb, const Transform& tb, double margin);

/// The same manifold seen from the other shape: the normal reversed, the anchors and the halves
/// of each id swapped.
Manifold swapped(const Manifold& m);

} // namespace pba::contact
