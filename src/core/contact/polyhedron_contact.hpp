#pragma once
// The two kinds of manifold between convex polyhedra, once the separating-axis test has chosen
// its axis: a face of one against the other's most anti-parallel face (clipped, up to four
// points), or two edges (one point).
#include "convex_polyhedron.hpp"
#include "manifold.hpp"
#include "separating_axis.hpp"

namespace pba::contact {

/// Which shape a contact's reference face belongs to: the manifold's normal points from A to B
/// whichever it is, and its ids name A's feature first.
enum class Reference { A, B };

/// The reference face `face` of `ref` (at `refPose`) against `inc` (at `incPose`): inc's face
/// most anti-parallel to it, clipped by the reference face's side planes; the points at most
/// `margin` above the reference plane, reduced to four (reduceManifold). A point's id is the
/// reference face and an incident vertex, a reference edge and an incident edge where the
/// two cross, or a reference vertex and the incident face.
Manifold faceContact(const ConvexPolyhedron& ref, const Transform& refPose, const ConvexPolyhedron& inc,
                     const Transform& incPose, std::uint32_t face, Reference which, double margin);

/// One point midway between the closest points of the query's two edges, with the query's
/// normal and separation; none when that separation is above `margin`.
Manifold edgeContact(const ConvexPolyhedron& a, const Transform& ta, const ConvexPolyhedron& b, const Transform& tb,
                     const EdgeQuery& query, double margin);

/// A candidate point of a face contact: on the incident face, in the reference frame. Left
/// uninitialised when made, so that room for many costs nothing.
struct ClipPoint {
    dvec3 position;
    double separation;
    std::uint32_t id;
};

} // namespace pba::contact
