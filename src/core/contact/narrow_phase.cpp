#include "contact/narrow_phase.hpp"

#include <algorithm>

#include "contact/polyhedron_contact.hpp"
#include "contact/separating_axis.hpp"
#include "contact/sphere_contact.hpp"

namespace pba::contact {

namespace {

/// How much further one axis must separate two polyhedra than another to be taken instead, as a
/// fraction of the smaller shape's bounding radius (half a millimetre for the 30 cm dice, as
/// Box2D's 0.1 linearSlop): a box resting on a box keeps one face and its four points rather
/// than flickering between faces and edges whose separations differ by rounding.
constexpr double kAxisPreference = 2e-3;

/// Whether B's best face is the reference rather than A's: the one that separates the shapes
/// clearly further, and between two within `slack` of each other the larger face, which keeps
/// the choice steady as the pose wobbles and the same when A and B are swapped (A's on a tie).
bool referenceIsB(const FaceQuery& a, double areaA, const FaceQuery& b, double areaB, double slack)
{
    if (b.separation > a.separation + slack)
        return true;
    if (a.separation > b.separation + slack)
        return false;
    return areaB > areaA;
}

bool fits(const SatCache& cache, const ConvexPolyhedron& a, const ConvexPolyhedron& b)
{
    switch (cache.axis) {
    case SatCache::Axis::FaceA: return cache.indexA < a.faces.size();
    case SatCache::Axis::FaceB: return cache.indexB < b.faces.size();
    case SatCache::Axis::Edges: return cache.indexA < a.edges.size() && cache.indexB < b.edges.size();
    case SatCache::Axis::None: return false;
    }
    return false;
}

/// The last step's axis measured as the full test measures it, so that a pair it still
/// separates by more than the margin can skip that test, which would find no contact either:
/// a face's separation is one the full test takes the largest of, and an edge pair's is too
/// while the two edges still meet on the Gauss map (-infinity otherwise: no shortcut).
double cachedSeparation(const SatCache& cache, const ConvexPolyhedron& a, const Transform& bInA, const ConvexPolyhedron& b,
                        const Transform& aInB)
{
    if (!fits(cache, a, b))
        return -INFINITY;
    switch (cache.axis) {
    case SatCache::Axis::FaceA: return faceSeparation(a, b, bInA, cache.indexA);
    case SatCache::Axis::FaceB: return faceSeparation(b, a, aInB, cache.indexB);
    case SatCache::Axis::Edges: return edgePair(a, b, bInA, cache.indexA, cache.indexB).separation;
    case SatCache::Axis::None: break;
    }
    return -INFINITY;
}

void remember(SatCache* cache, SatCache::Axis axis, std::uint32_t indexA, std::uint32_t indexB)
{
    if (cache)
        *cache = {axis, indexA, indexB};
}

Manifold polyhedra(const ConvexPolyhedron& a, const Transform& ta, const ConvexPolyhedron& b, const Transform& tb,
                   double margin, SatCache* cache)
{
    const Transform bInA = relativeTransform(ta, tb), aInB = relativeTransform(tb, ta);
    if (cache && cachedSeparation(*cache, a, bInA, b, aInB) > margin)
        return {};
    const FaceQuery faceA = queryFaces(a, b, bInA, margin);
    if (faceA.separation > margin) {
        remember(cache, SatCache::Axis::FaceA, faceA.face, 0);
        return {};
    }
    const FaceQuery faceB = queryFaces(b, a, aInB, margin);
    if (faceB.separation > margin) {
        remember(cache, SatCache::Axis::FaceB, 0, faceB.face);
        return {};
    }
    const EdgeQuery edges = queryEdges(a, b, bInA, margin);
    if (edges.separation > margin) {
        remember(cache, SatCache::Axis::Edges, edges.edgeA, edges.edgeB);
        return {};
    }
    const double slack = kAxisPreference * std::min(a.boundingRadius, b.boundingRadius);
    const bool useB = referenceIsB(faceA, a.faces[faceA.face].area, faceB, b.faces[faceB.face].area, slack);
    // An edge pair is taken only when it separates the shapes clearly further than that face
    // (so the axis taken is never more than `slack` worse than the best).
    if (edges.separation > (useB ? faceB.separation : faceA.separation) + slack) {
        remember(cache, SatCache::Axis::Edges, edges.edgeA, edges.edgeB);
        return edgeContact(a, ta, b, tb, edges, margin);
    }
    Manifold m;
    if (useB) {
        remember(cache, SatCache::Axis::FaceB, 0, faceB.face);
        m = faceContact(b, tb, a, ta, faceB.face, Reference::B, margin);
    } else {
        remember(cache, SatCache::Axis::FaceA, faceA.face, 0);
        m = faceContact(a, ta, b, tb, faceA.face, Reference::A, margin);
    }
    // A face axis taken over a slightly better edge axis can clip the incident face away
    // entirely (two edges crossing just beyond the face): the edges' point is the contact then.
    if (m.count == 0)
        m = edgeContact(a, ta, b, tb, edges, margin);
    return m;
}

} // namespace

Manifold collide(const CollisionShape& a, const Transform& ta, const CollisionShape& b, const Transform& tb,
                 double margin, SatCache* cache)
{
    using Kind = CollisionShape::Kind;
    if (a.kind == Kind::Sphere && b.kind == Kind::Sphere)
        return sphereSphere(a.radius, ta, b.radius, tb, margin);
    if (b.kind == Kind::Sphere)
        return polyhedronSphere(*a.polyhedron, ta, b.radius, tb, margin);
    if (a.kind == Kind::Sphere)
        return swapped(polyhedronSphere(*b.polyhedron, tb, a.radius, ta, margin));
    return polyhedra(*a.polyhedron, ta, *b.polyhedron, tb, margin, cache);
}

} // namespace pba::contact
