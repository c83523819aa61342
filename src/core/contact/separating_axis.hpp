#pragma once
// The separating-axis test between two convex polyhedra, in A's frame (Gregorius, "The
// Separating Axis Test between Convex Polyhedra", GDC 2013): the faces of A, the faces of B, and
// the pairs of edges whose arcs cross on the Gauss map (the pairs whose cross product is a face
// normal of the Minkowski difference; every other pair's axis is no better than some face's).
// Each query's separation is exact along its axis: the gap between the two shapes' projections,
// negative when they overlap.
#include <cmath>

#include "convex_polyhedron.hpp"
#include "manifold.hpp"

namespace pba::contact {

/// `b`'s frame seen from `a`'s: x_a = result.apply(x_b).
inline Transform relativeTransform(const Transform& a, const Transform& b)
{
    const dmat3 toA = glm::transpose(a.rotation);
    return {toA * (b.position - a.position), toA * b.rotation};
}

struct FaceQuery {
    double separation = -INFINITY;
    std::uint32_t face = 0;
};

struct EdgeQuery {
    double separation = -INFINITY; ///< -infinity when no pair of edges meets on the Gauss map
    std::uint32_t edgeA = 0, edgeB = 0;
    dvec3 normal{0.0}; ///< A's frame, from A to B
};

/// How far `b` (at `bInA`) lies beyond `a`'s face `face`: the least distance of b's vertices
/// above the face's plane.
double faceSeparation(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Transform& bInA, std::uint32_t face);

/// The face of `a` whose plane `b` lies furthest beyond (the first on a tie). Stops at the first
/// face with a separation above `stopAbove`.
FaceQuery queryFaces(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Transform& bInA, double stopAbove);

/// The pair of edges, one of `a` and one of `b`, that meet on the Gauss map with the largest
/// separation along their common normal (parallel pairs are left to the faces). Stops at the
/// first pair with a separation above `stopAbove`.
EdgeQuery queryEdges(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Transform& bInA, double stopAbove);

/// One pair's query, as queryEdges would find it: separation -infinity when the two edges do not
/// meet on the Gauss map or are parallel. Between two boxes, the pair of their directions: the
/// edges along them that queryEdges would find now, which may be others than these.
EdgeQuery edgePair(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Transform& bInA, std::uint32_t edgeA,
                   std::uint32_t edgeB);

} // namespace pba::contact
