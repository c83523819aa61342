#pragma once
// The narrow phase: the contact manifold of two convex shapes at their poses. Every pair of
// shapes pba has reduces to three: sphere-sphere, sphere-polyhedron and polyhedron-polyhedron
// (boxes, cylinders as prisms, meshes as their convex hulls).
#include <memory>

#include "convex_polyhedron.hpp"
#include "manifold.hpp"
#include "pba/shape.hpp"

namespace pba::contact {

struct CollisionShape {
    enum class Kind { Sphere, Polyhedron };
    Kind kind = Kind::Sphere;
    double radius = 0.0; ///< a sphere's
    std::shared_ptr<const ConvexPolyhedron> polyhedron; ///< otherwise

    /// A rigid body's shape as it collides: a sphere as itself, a box as a box, a cylinder as a
    /// prism of kCylinderRimPoints sides, a mesh as its convex hull.
    static CollisionShape of(const Shape& shape);
    double boundingRadius() const { return kind == Kind::Sphere ? radius : polyhedron->boundingRadius; }
};

/// What the separating-axis test found last step for a pair, so that the next step can start
/// from it (a resting pair keeps its axis from step to step). Owned by the contact cache.
struct SatCache {
    enum class Axis : std::uint8_t { None, FaceA, FaceB, Edges };
    Axis axis = Axis::None;
    std::uint32_t indexA = 0, indexB = 0; ///< the face, or the two edges
};

/// The manifold of `a` at `ta` and `b` at `tb`: the normal points from a to b; points further
/// apart than `margin` (a speculative distance, >= 0) are left out, and a pair further apart
/// than that has count 0. At most Manifold::kMaxPoints points, chosen to keep the deepest and
/// the largest area (a box lying on a face keeps its four corners). `cache` may be null.
///
/// Between polyhedra the normal is a face's unless an edge pair separates the shapes clearly
/// further (by 0.2% of the smaller shape's bounding radius), so that resting contact keeps one
/// steady manifold; between two faces within that of each other, the larger is the reference.
/// Swapping a and b therefore reverses the normal and keeps the points (anchors and ids' halves
/// exchanged), except between two faces of equal area that tie, where each order takes its own
/// A's face and the points may differ. With a cache, a pair the cached axis still separates by
/// more than the margin skips the full test (which would find count 0 as well); otherwise the
/// cache is only written, so the manifold is the same with or without it (to the last bit, but
/// for a compiler that fuses the same product differently in the two places it computes it).
Manifold collide(const CollisionShape& a, const Transform& ta, const CollisionShape& b, const Transform& tb,
                 double margin, SatCache* cache = nullptr);

} // namespace pba::contact
