#pragma once
// The shape of a rigid body: what its mass properties are computed from, where the room touches
// it, and what is drawn. Each shape is centred on its centre of mass (a mesh is moved there), so
// a body's position is its centre of mass and its orientation turns the shape about it.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "pba/body.hpp"
#include "pba/mass_properties.hpp"
#include "pba/math.hpp"
#include "pba/mesh.hpp"

namespace pba {

enum class ShapeType { Box, Sphere, Cylinder, Mesh };

/// "box", "sphere", "cylinder", "mesh".
std::string_view shapeTypeName(ShapeType type);

struct Shape {
    ShapeType type = ShapeType::Box;
    dvec3 size{1.0};    ///< box: side lengths along x, y, z
    double radius = 0.5; ///< sphere, cylinder
    double height = 1.0; ///< cylinder, along y
    /// mesh: vertices (already centred on the centre of mass) and triangles, counter-clockwise
    /// seen from outside.
    std::vector<dvec3> vertices;
    std::vector<std::uint32_t> triangles;

    static Shape box(const dvec3& size);
    static Shape sphere(double radius);
    static Shape cylinder(double radius, double height);
    /// A closed triangle mesh, moved so that its centre of mass (at unit density) is the origin.
    /// std::invalid_argument as meshMassProperties.
    static Shape mesh(std::vector<dvec3> vertices, std::vector<std::uint32_t> triangles);
};

/// The shape's mass properties at `density` (kg/m^3), about its centre (the origin).
MassProperties massPropertiesOf(const Shape& shape, double density);

/// The points of the shape, in its own frame, at which contact with a plane is sought: a box's
/// eight corners, a mesh's vertices, a cylinder's two rims at kCylinderRimPoints points each
/// (a polygon: enough for a cylinder standing on its end or lying on its side). A sphere has
/// none: its contact is the point of the sphere closest to each plane (see sphereRadius).
std::vector<dvec3> contactPointsOf(const Shape& shape);
inline constexpr int kCylinderRimPoints = 24;

/// Points spread over the shape's surface, each with its share of the area (the shares add up to
/// 1): a box's faces and a cylinder's caps and side in a grid of cells, a sphere in rings of
/// equal area about its y axis, a mesh's triangles at their centroids.
std::vector<SurfaceSample> surfaceSamplesOf(const Shape& shape);

/// A drawable mesh of the shape (positions, outward normals, triangles), flat-shaded faces for a
/// box or a mesh, smooth for a sphere or a cylinder's side.
Mesh drawMeshOf(const Shape& shape);

} // namespace pba
