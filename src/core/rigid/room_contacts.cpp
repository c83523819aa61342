#include "rigid/room_contacts.hpp"

#include <algorithm>
#include <cmath>

#include "contact/manifold_reduction.hpp"

namespace pba::rigid {

namespace {

using contact::CollisionShape;
using contact::Feature;
using contact::makeFeatureId;
using contact::Transform;

/// The candidates of one surface before reduction: a box has 8 corners, a cylinder's prism 48.
struct Candidates {
    std::vector<ContactPoint> points;
    void add(const dvec3& normal, const dvec3& anchorA, const dvec3& at, double gap, std::uint32_t vertex,
             std::uint32_t surface)
    {
        ContactPoint p;
        p.normal = normal;
        p.anchorA = anchorA;
        p.anchorB = at + normal * gap; // on the surface, the world's frame
        p.point = at + normal * (0.5 * gap);
        p.separation = gap;
        p.id = makeFeatureId(Feature::Vertex, vertex, Feature::Face, surface);
        points.push_back(p);
    }
};

void emit(Candidates& c, BodyIndex body, BodyIndex surfaceBody, std::vector<Contact>& out)
{
    if (c.points.empty())
        return;
    Contact contact;
    contact.a = body;
    contact.b = surfaceBody;
    // Four or more corners touching (within kNear of the deepest) are the contact: what else the
    // step's reach takes in is left out. A 50 cm box resting on a face at dt 0.32 s, whose reach
    // (half g dt^2) took in its top corners, kept two of them, the furthest from the deepest, in
    // place of two it stood on, and tipped over with a third more energy.
    constexpr double kNear = 0.01;
    const ContactPoint& deepestPoint =
        *std::min_element(c.points.begin(), c.points.end(),
                          [](const ContactPoint& p, const ContactPoint& q) { return p.separation < q.separation; });
    const double deepest = deepestPoint.separation;
    // A surface's points share its normal but on the shaft's round wall, where each has its own:
    // the deepest's plane is the contact's there.
    const dvec3 plane = deepestPoint.normal;
    const auto isNear = [&](const ContactPoint& p) { return p.separation <= deepest + kNear; };
    int candidates = int(c.points.size());
    if (const auto touching = std::count_if(c.points.begin(), c.points.end(), isNear);
        touching >= 4 && touching < candidates) {
        std::stable_partition(c.points.begin(), c.points.end(), isNear);
        candidates = int(touching);
    }
    const int count = contact::reduceManifold(std::span{c.points.data(), std::size_t(candidates)}, plane,
                                              [](const ContactPoint& p) { return p.point; });
    contact.count = count;
    for (int k = 0; k < count; ++k)
        contact.points[k] = c.points[k];
    out.push_back(contact);
    c.points.clear();
}

} // namespace

void collideWithRoom(const CollisionShape& shape, const Transform& pose, std::span<const Plane> planes, double margin,
                     BodyIndex body, BodyIndex firstSurface, std::vector<Contact>& out, std::optional<double> sphereMargin)
{
    thread_local Candidates candidates;
    const dvec3& x = pose.position;
    const bool sphere = shape.kind == CollisionShape::Kind::Sphere;
    const double reach = shape.boundingRadius() + sphereMargin.value_or(margin);
    for (std::size_t p = 0; p < planes.size(); ++p) {
        const Plane& plane = planes[p];
        const double centre = plane.distance(x);
        const bool inShaft = plane.holeRadius > 0.0 && centre < 0.0 && plane.overHole(x);
        if (!inShaft && centre > reach)
            continue;
        const std::uint32_t surface = inShaft ? shaftSurface(planes.size(), p) : std::uint32_t(p);
        if (sphere) {
            const double r = shape.radius;
            if (inShaft) {
                // The point nearest the shaft's wall: on the sphere's equator, away from the axis.
                const dvec3 rho = plane.fromHoleAxis(x);
                const double len = glm::length(rho);
                const double gap = plane.holeRadius - len - r;
                if (len > 0.0 && gap < margin) {
                    const dvec3 n = rho / len;
                    candidates.add(n, glm::transpose(pose.rotation) * (n * r), x + n * r, gap, 0, surface);
                }
            } else {
                const dvec3 at = x - r * plane.normal;
                const double gap = centre - r;
                if (gap < margin && !plane.overHole(at))
                    candidates.add(-plane.normal, glm::transpose(pose.rotation) * (-r * plane.normal), at, gap, 0,
                                   surface);
            }
        } else {
            const auto& vertices = shape.polyhedron->vertices;
            for (std::size_t k = 0; k < vertices.size(); ++k) {
                const dvec3 at = pose.apply(vertices[k]);
                if (inShaft) {
                    const dvec3 rho = plane.fromHoleAxis(at);
                    const double len = glm::length(rho);
                    const double gap = plane.holeRadius - len;
                    if (len > 0.0 && gap < margin)
                        candidates.add(rho / len, vertices[k], at, gap, std::uint32_t(k), surface);
                } else if (const double gap = plane.distance(at); gap < margin && !plane.overHole(at)) {
                    candidates.add(-plane.normal, vertices[k], at, gap, std::uint32_t(k), surface);
                }
            }
        }
        emit(candidates, body, firstSurface + surface, out);
    }
}

bool pushOutOfRoom(const CollisionShape& shape, dvec3& x, const dquat& q, std::span<const Plane> planes)
{
    thread_local std::vector<Contact> beyond;
    beyond.clear();
    collideWithRoom(shape, Transform{x, glm::mat3_cast(q)}, planes, 0.0, 0, 0, beyond);
    bool moved = false;
    for (const Contact& c : beyond) {
        const ContactPoint* deepest = nullptr;
        for (int i = 0; i < c.count; ++i)
            if (c.points[i].separation < 0.0 && (!deepest || c.points[i].separation < deepest->separation))
                deepest = &c.points[i];
        if (deepest) {
            x += deepest->separation * deepest->normal; // the normal points into the surface
            moved = true;
        }
    }
    return moved;
}

} // namespace pba::rigid
