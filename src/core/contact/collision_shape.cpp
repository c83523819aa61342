#include <memory>
#include <stdexcept>

#include "contact/narrow_phase.hpp"

namespace pba::contact {

CollisionShape CollisionShape::of(const Shape& shape)
{
    CollisionShape c;
    switch (shape.type) {
    case ShapeType::Sphere:
        c.kind = Kind::Sphere;
        c.radius = shape.radius;
        return c;
    case ShapeType::Box:
        c.polyhedron = std::make_shared<const ConvexPolyhedron>(ConvexPolyhedron::box(0.5 * shape.size));
        break;
    case ShapeType::Cylinder:
        c.polyhedron = std::make_shared<const ConvexPolyhedron>(
            ConvexPolyhedron::prism(shape.radius, shape.height, kCylinderRimPoints));
        break;
    case ShapeType::Mesh:
        c.polyhedron = std::make_shared<const ConvexPolyhedron>(ConvexPolyhedron::hull(shape.vertices));
        break;
    }
    c.kind = Kind::Polyhedron;
    return c;
}

} // namespace pba::contact
