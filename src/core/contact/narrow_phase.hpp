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
Manifold collide(const CollisionShape& a, const Transform& ta, const CollisionShape& b, const Transform& tb,
                 double margin, SatCache* cache = nullptr);

} // namespace pba::contact
