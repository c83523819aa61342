// TEMPORARY: stands in for the narrow phase until its branch is merged (spheres only).
#include "contact/narrow_phase.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pba::contact {

ConvexPolyhedron ConvexPolyhedron::box(const dvec3& h)
{
    ConvexPolyhedron p;
    for (int k = 0; k < 8; ++k)
        p.vertices.push_back(dvec3((k & 1) ? h.x : -h.x, (k & 2) ? h.y : -h.y, (k & 4) ? h.z : -h.z));
    p.boundingRadius = glm::length(h);
    return p;
}

ConvexPolyhedron ConvexPolyhedron::prism(double radius, double height, int sides)
{
    ConvexPolyhedron p;
    for (int rim = 0; rim < 2; ++rim)
        for (int k = 0; k < sides; ++k) {
            const double a = 2.0 * std::numbers::pi * k / sides;
            p.vertices.push_back(dvec3(radius * std::cos(a), rim ? 0.5 * height : -0.5 * height, radius * std::sin(a)));
        }
    p.boundingRadius = std::sqrt(radius * radius + 0.25 * height * height);
    return p;
}

ConvexPolyhedron ConvexPolyhedron::hull(std::span<const dvec3> points)
{
    ConvexPolyhedron p;
    p.vertices.assign(points.begin(), points.end());
    for (const dvec3& v : points)
        p.boundingRadius = std::max(p.boundingRadius, glm::length(v));
    return p;
}

std::uint32_t ConvexPolyhedron::support(const dvec3&) const { return 0; }

CollisionShape CollisionShape::of(const Shape& shape)
{
    CollisionShape c;
    switch (shape.type) {
    case ShapeType::Sphere: c.kind = Kind::Sphere; c.radius = shape.radius; return c;
    case ShapeType::Box: c.polyhedron = std::make_shared<ConvexPolyhedron>(ConvexPolyhedron::box(0.5 * shape.size)); break;
    case ShapeType::Cylinder:
        c.polyhedron = std::make_shared<ConvexPolyhedron>(ConvexPolyhedron::prism(shape.radius, shape.height, kCylinderRimPoints));
        break;
    case ShapeType::Mesh: c.polyhedron = std::make_shared<ConvexPolyhedron>(ConvexPolyhedron::hull(shape.vertices)); break;
    }
    c.kind = Kind::Polyhedron;
    return c;
}

Manifold collide(const CollisionShape& a, const Transform& ta, const CollisionShape& b, const Transform& tb, double margin,
                 SatCache*)
{
    Manifold m;
    if (a.kind != CollisionShape::Kind::Sphere || b.kind != CollisionShape::Kind::Sphere)
        return m;
    const dvec3 d = tb.position - ta.position;
    const double len = glm::length(d);
    const double sep = len - a.radius - b.radius;
    if (sep > margin)
        return m;
    m.normal = len > 0.0 ? d / len : dvec3(0.0, 1.0, 0.0);
    m.count = 1;
    const dvec3 pa = ta.position + m.normal * a.radius, pb = tb.position - m.normal * b.radius;
    m.points[0].anchorA = ta.applyInverse(pa) - dvec3(0.0) ;
    m.points[0].anchorA = glm::transpose(ta.rotation) * (pa - ta.position);
    m.points[0].anchorB = glm::transpose(tb.rotation) * (pb - tb.position);
    m.points[0].point = 0.5 * (pa + pb);
    m.points[0].separation = sep;
    m.points[0].id = 0;
    return m;
}

} // namespace pba::contact
