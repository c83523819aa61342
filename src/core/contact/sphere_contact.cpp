#include "contact/sphere_contact.hpp"

#include <algorithm>
#include <cmath>

namespace pba::contact {

namespace {

/// The sphere's own feature in an id: it has only its surface.
constexpr std::uint32_t kSphereIndex = 0;

/// A point of a polyhedron's surface and the feature it lies on.
struct SurfacePoint {
    dvec3 position{0.0};
    double distance2 = INFINITY;
    Feature kind = Feature::Face;
    std::uint32_t index = 0;
};

/// The point of face `face` closest to `c`, which lies above the face's plane: its projection
/// when that falls inside the face, else the closest point of the face's edges.
SurfacePoint closestOnFace(const ConvexPolyhedron& p, std::uint32_t face, const dvec3& c)
{
    const ConvexPolyhedron::Face& f = p.faces[face];
    const double height = glm::dot(f.normal, c) - f.offset;
    const dvec3 projected = c - height * f.normal;
    SurfacePoint best;
    bool inside = true;
    for (std::uint32_t k = 0; k < f.count; ++k) {
        const std::uint32_t tailIndex = p.faceVertices[f.first + k], headIndex = p.faceVertices[f.first + (k + 1) % f.count];
        const dvec3 &tail = p.vertices[tailIndex], edge = p.vertices[headIndex] - tail;
        if (glm::dot(glm::cross(f.normal, edge), projected - tail) >= 0.0)
            continue;
        inside = false;
        const double length2 = glm::dot(edge, edge);
        const double t = length2 > 0.0 ? std::clamp(glm::dot(c - tail, edge) / length2, 0.0, 1.0) : 0.0;
        const dvec3 q = tail + t * edge;
        const double d2 = glm::dot(c - q, c - q);
        if (d2 < best.distance2) {
            best.position = q;
            best.distance2 = d2;
            best.kind = t == 0.0 || t == 1.0 ? Feature::Vertex : Feature::Edge;
            best.index = t == 0.0 ? tailIndex : t == 1.0 ? headIndex : p.faceEdges[f.first + k];
        }
    }
    if (inside)
        return {projected, height * height, Feature::Face, face};
    return best;
}

} // namespace

Manifold sphereSphere(double ra, const Transform& ta, double rb, const Transform& tb, double margin)
{
    const dvec3 d = tb.position - ta.position;
    const double distance = glm::length(d);
    Manifold m;
    const double separation = distance - ra - rb;
    if (!(separation <= margin))
        return m;
    m.normal = distance > 0.0 ? d / distance : dvec3(0.0, 1.0, 0.0);
    m.count = 1;
    const dvec3 onA = ta.position + ra * m.normal, onB = tb.position - rb * m.normal;
    m.points[0] = {ta.applyInverse(onA), tb.applyInverse(onB), 0.5 * (onA + onB), separation,
                   makeFeatureId(Feature::Face, kSphereIndex, Feature::Face, kSphereIndex)};
    return m;
}

Manifold polyhedronSphere(const ConvexPolyhedron& a, const Transform& ta, double rb, const Transform& tb, double margin)
{
    const dvec3 c = ta.applyInverse(tb.position);
    // The face the centre is highest above (the first on a tie): inside, it is the way out.
    std::uint32_t top = 0;
    double height = -INFINITY;
    for (std::uint32_t i = 0; i < a.faces.size(); ++i)
        if (const double h = glm::dot(a.faces[i].normal, c) - a.faces[i].offset; h > height) {
            height = h;
            top = i;
        }
    SurfacePoint closest{c - height * a.faces[top].normal, 0.0, Feature::Face, top};
    double distance = height;
    dvec3 normal = a.faces[top].normal;
    if (height > 0.0) {
        // Outside: the closest point lies on a face the centre is above (the first on a tie).
        closest = SurfacePoint{};
        for (std::uint32_t i = 0; i < a.faces.size(); ++i)
            if (glm::dot(a.faces[i].normal, c) - a.faces[i].offset > 0.0)
                if (const SurfacePoint q = closestOnFace(a, i, c); q.distance2 < closest.distance2)
                    closest = q;
        distance = std::sqrt(closest.distance2);
        // So close that the direction is rounding: the face's normal is the direction then.
        if (distance > 1e-12 * a.boundingRadius)
            normal = (c - closest.position) / distance;
    }
    Manifold m;
    const double separation = distance - rb;
    if (!(separation <= margin))
        return m;
    m.normal = ta.rotation * normal;
    m.count = 1;
    const dvec3 onA = ta.apply(closest.position), onB = tb.position - rb * m.normal;
    m.points[0] = {closest.position, tb.applyInverse(onB), 0.5 * (onA + onB), separation,
                   makeFeatureId(closest.kind, closest.index, Feature::Face, kSphereIndex)};
    return m;
}

Manifold swapped(const Manifold& m)
{
    Manifold s = m;
    s.normal = -m.normal;
    for (int k = 0; k < m.count; ++k) {
        ManifoldPoint& p = s.points[static_cast<std::size_t>(k)];
        std::swap(p.anchorA, p.anchorB);
        p.id = (p.id >> 16) | (p.id << 16);
    }
    return s;
}

} // namespace pba::contact
