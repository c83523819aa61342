#pragma once
// A convex polyhedron in a body's frame, as the narrow phase reads it: vertices, faces (each a
// plane and a loop of vertices) and edges (each with the two faces that meet there, which is the
// edge's arc on the Gauss map that the separating-axis test prunes edge pairs with, as in
// Gregorius, "The Separating Axis Test between Convex Polyhedra", GDC 2013). A box is one, a
// cylinder collides as a prism of kCylinderRimPoints sides (the same polygon the room's contacts
// use), and a mesh as its convex hull.
#include <cstdint>
#include <span>
#include <vector>

#include "pba/math.hpp"

namespace pba::contact {

struct ConvexPolyhedron {
    struct Face {
        dvec3 normal{0.0};  ///< outward, unit
        double offset = 0.0; ///< the face's plane: dot(normal, x) == offset
        std::uint32_t first = 0; ///< its loop: faceVertices[first, first + count)
        std::uint32_t count = 0;
        double area = 0.0; ///< of its loop (breaks near ties between two faces for the reference)
    };
    /// Seen from outside, leftFace lies to the left of the edge run from tail to head: its loop
    /// (counter-clockwise) runs tail -> head, rightFace's runs head -> tail.
    struct Edge {
        std::uint32_t tail = 0, head = 0;      ///< vertex indices
        std::uint32_t leftFace = 0, rightFace = 0; ///< the two faces that share it
    };

    std::vector<dvec3> vertices;
    std::vector<Face> faces;
    /// Each face's vertex loop, counter-clockwise seen from outside.
    std::vector<std::uint32_t> faceVertices;
    /// Beside faceVertices: the edge from loop vertex k to loop vertex k + 1 (the last to the
    /// first), so that a clipped point names the edge it lies on.
    std::vector<std::uint32_t> faceEdges;
    std::vector<Edge> edges; ///< each edge once
    double boundingRadius = 0.0; ///< the furthest vertex from the origin
    /// Non-zero only for ConvexPolyhedron::box (whose vertex i has the sign of bit 0 in x, bit 1 in
    /// y, bit 2 in z, and face 2k + s the normal of sign s along axis k): its half extents, which
    /// let support and the separating-axis test between two boxes work in closed form.
    dvec3 boxHalfExtents{0.0};

    /// A box centred on the origin, axis-aligned.
    static ConvexPolyhedron box(const dvec3& halfExtents);
    /// A right prism about the y axis, `sides` vertices on each of its two rims (a cylinder's
    /// stand-in), centred on the origin. Rim vertex k sits at angle 2 pi k / sides from +x
    /// towards +z, the bottom rim first, as contactPointsOf places a cylinder's.
    static ConvexPolyhedron prism(double radius, double height, int sides);
    /// The convex hull of `points` (Qhull), with coplanar triangles merged into one face.
    /// std::invalid_argument when the points span no volume.
    static ConvexPolyhedron hull(std::span<const dvec3> points);
    /// A polyhedron from its vertices and faces: each face's loop counter-clockwise seen from
    /// outside and its outward unit normal. Finds the edges and each face's offset (its furthest
    /// vertex along the normal). std::invalid_argument when a face has fewer than three
    /// vertices or the faces do not close (an edge not shared by exactly two faces, in opposite
    /// directions).
    static ConvexPolyhedron fromFaces(std::vector<dvec3> vertices, std::span<const std::vector<std::uint32_t>> loops,
                                      std::span<const dvec3> normals);

    bool isBox() const { return boxHalfExtents.x > 0.0; }
    /// The index of the vertex furthest along `direction` (the first such on a tie).
    std::uint32_t support(const dvec3& direction) const;
    /// The edge between vertices `tail` and `head` (either way round); edges.size() if none.
    std::uint32_t edgeBetween(std::uint32_t tail, std::uint32_t head) const;
    /// A face's vertex loop (indices into vertices).
    std::span<const std::uint32_t> loop(const Face& face) const { return {faceVertices.data() + face.first, face.count}; }
};

} // namespace pba::contact
