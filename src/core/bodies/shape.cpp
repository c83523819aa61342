#include "pba/shape.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pba {

std::string_view shapeTypeName(ShapeType type)
{
    switch (type) {
    case ShapeType::Box: return "box";
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Cylinder: return "cylinder";
    case ShapeType::Mesh: return "mesh";
    }
    return "?";
}

Shape Shape::box(const dvec3& size)
{
    Shape s;
    s.type = ShapeType::Box;
    s.size = size;
    return s;
}

Shape Shape::sphere(double radius)
{
    Shape s;
    s.type = ShapeType::Sphere;
    s.radius = radius;
    return s;
}

Shape Shape::cylinder(double radius, double height)
{
    Shape s;
    s.type = ShapeType::Cylinder;
    s.radius = radius;
    s.height = height;
    return s;
}

Shape Shape::mesh(std::vector<dvec3> vertices, std::vector<std::uint32_t> triangles)
{
    const dvec3 centre = meshMassProperties(vertices, triangles, 1.0).centre; // checks the mesh
    for (dvec3& v : vertices)
        v -= centre;
    Shape s;
    s.type = ShapeType::Mesh;
    s.vertices = std::move(vertices);
    s.triangles = std::move(triangles);
    return s;
}

MassProperties massPropertiesOf(const Shape& shape, double density)
{
    switch (shape.type) {
    case ShapeType::Box: return boxMassProperties(shape.size, density);
    case ShapeType::Sphere: return sphereMassProperties(shape.radius, density);
    case ShapeType::Cylinder: return cylinderMassProperties(shape.radius, shape.height, density);
    case ShapeType::Mesh: return meshMassProperties(shape.vertices, shape.triangles, density);
    }
    throw std::invalid_argument("unknown shape");
}

namespace {

/// Point k of n around a circle of `radius` in the xz plane, at height y.
dvec3 onRim(int k, int n, double radius, double y)
{
    const double angle = 2.0 * std::numbers::pi * k / n;
    return {radius * std::cos(angle), y, radius * std::sin(angle)};
}

} // namespace

std::vector<dvec3> contactPointsOf(const Shape& shape)
{
    std::vector<dvec3> points;
    switch (shape.type) {
    case ShapeType::Box:
        for (int corner = 0; corner < 8; ++corner)
            points.push_back(0.5 * shape.size *
                             dvec3(corner & 1 ? 1.0 : -1.0, corner & 2 ? 1.0 : -1.0, corner & 4 ? 1.0 : -1.0));
        break;
    case ShapeType::Cylinder:
        for (const double y : {-0.5 * shape.height, 0.5 * shape.height})
            for (int k = 0; k < kCylinderRimPoints; ++k)
                points.push_back(onRim(k, kCylinderRimPoints, shape.radius, y));
        break;
    case ShapeType::Mesh: points = shape.vertices; break;
    case ShapeType::Sphere: break;
    }
    return points;
}

namespace {

/// Every sample's area over the total: the shares.
std::vector<SurfaceSample> shared(std::vector<SurfaceSample> samples)
{
    double total = 0.0;
    for (const SurfaceSample& s : samples)
        total += s.share;
    for (SurfaceSample& s : samples)
        s.share /= total;
    return samples;
}

std::vector<SurfaceSample> boxSamples(const dvec3& size)
{
    constexpr int kCells = 4; // a face's cells a side
    std::vector<SurfaceSample> samples;
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        const double area = size[u] * size[w] / (kCells * kCells);
        for (const double side : {-0.5, 0.5})
            for (int i = 0; i < kCells; ++i)
                for (int j = 0; j < kCells; ++j) {
                    dvec3 p(0.0);
                    p[axis] = side * size[axis];
                    p[u] = ((i + 0.5) / kCells - 0.5) * size[u];
                    p[w] = ((j + 0.5) / kCells - 0.5) * size[w];
                    samples.push_back({p, area});
                }
    }
    return samples;
}

std::vector<SurfaceSample> sphereSamples(double radius)
{
    // Bands of equal height have equal area (Archimedes): each band's points at its middle.
    constexpr int kBands = 8, kAround = 16;
    std::vector<SurfaceSample> samples;
    for (int b = 0; b < kBands; ++b) {
        const double y = radius * (-1.0 + (2.0 * b + 1.0) / kBands);
        for (int k = 0; k < kAround; ++k) {
            const dvec3 ring = onRim(k, kAround, std::sqrt(radius * radius - y * y), y);
            samples.push_back({ring, 1.0});
        }
    }
    return samples;
}

std::vector<SurfaceSample> cylinderSamples(double radius, double height)
{
    constexpr int kAround = 16, kRows = 4, kRings = 3;
    std::vector<SurfaceSample> samples;
    const double side = 2.0 * std::numbers::pi * radius * height / (kAround * kRows);
    for (int row = 0; row < kRows; ++row)
        for (int k = 0; k < kAround; ++k)
            samples.push_back({onRim(k, kAround, radius, ((row + 0.5) / kRows - 0.5) * height), side});
    for (const double y : {-0.5 * height, 0.5 * height})
        for (int ring = 0; ring < kRings; ++ring) {
            // Rings of equal area on the cap: radii between sqrt(ring / kRings) R and the next.
            const double inner = radius * std::sqrt(double(ring) / kRings), outer = radius * std::sqrt(double(ring + 1) / kRings);
            const double area = std::numbers::pi * (outer * outer - inner * inner) / kAround;
            for (int k = 0; k < kAround; ++k)
                samples.push_back({onRim(k, kAround, 0.5 * (inner + outer), y), area});
        }
    return samples;
}

std::vector<SurfaceSample> meshSamples(const Shape& shape)
{
    std::vector<SurfaceSample> samples;
    for (std::size_t t = 0; t + 2 < shape.triangles.size(); t += 3) {
        const dvec3 &a = shape.vertices[shape.triangles[t]], &b = shape.vertices[shape.triangles[t + 1]],
                    &c = shape.vertices[shape.triangles[t + 2]];
        samples.push_back({(a + b + c) / 3.0, 0.5 * glm::length(glm::cross(b - a, c - a))});
    }
    return samples;
}

} // namespace

std::vector<SurfaceSample> surfaceSamplesOf(const Shape& shape)
{
    switch (shape.type) {
    case ShapeType::Box: return shared(boxSamples(shape.size));
    case ShapeType::Sphere: return shared(sphereSamples(shape.radius));
    case ShapeType::Cylinder: return shared(cylinderSamples(shape.radius, shape.height));
    case ShapeType::Mesh: return shared(meshSamples(shape));
    }
    return {};
}

namespace {

/// Triangles with their own vertices (flat shading): each face's normal at its three corners.
struct MeshBuilder {
    std::vector<glm::vec3> positions, normals;
    std::vector<std::uint32_t> indices;

    void vertex(const dvec3& p, const dvec3& n)
    {
        indices.push_back(static_cast<std::uint32_t>(positions.size()));
        positions.emplace_back(p);
        normals.emplace_back(n);
    }
    void flatTriangle(const dvec3& a, const dvec3& b, const dvec3& c)
    {
        const dvec3 n = glm::normalize(glm::cross(b - a, c - a));
        vertex(a, n), vertex(b, n), vertex(c, n);
    }
    Mesh take() { return Mesh(std::move(positions), std::move(normals), std::move(indices)); }
};

Mesh boxMesh(const dvec3& size)
{
    MeshBuilder m;
    const dvec3 h = 0.5 * size;
    for (int axis = 0; axis < 3; ++axis) {
        for (const double side : {-1.0, 1.0}) {
            // The face's two in-plane axes, ordered so that u x w points out of the box.
            dvec3 n(0.0), u(0.0), w(0.0);
            n[axis] = side;
            u[(axis + 1) % 3] = 1.0;
            w[(axis + 2) % 3] = side;
            const dvec3 c = n * h[axis];
            const dvec3 du = u * h[(axis + 1) % 3], dw = w * h[(axis + 2) % 3];
            m.flatTriangle(c - du - dw, c + du - dw, c + du + dw);
            m.flatTriangle(c - du - dw, c + du + dw, c - du + dw);
        }
    }
    return m.take();
}

Mesh sphereMesh(double radius)
{
    constexpr int kRings = 16, kSegments = 32;
    std::vector<glm::vec3> positions, normals;
    std::vector<std::uint32_t> indices;
    for (int i = 0; i <= kRings; ++i) {
        const double theta = std::numbers::pi * i / kRings;
        for (int j = 0; j <= kSegments; ++j) {
            const double phi = 2.0 * std::numbers::pi * j / kSegments;
            const dvec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            positions.emplace_back(radius * n);
            normals.emplace_back(n);
        }
    }
    for (int i = 0; i < kRings; ++i)
        for (int j = 0; j < kSegments; ++j) {
            const auto a = static_cast<std::uint32_t>(i * (kSegments + 1) + j), b = a + kSegments + 1;
            indices.insert(indices.end(), {a, a + 1, b, a + 1, b + 1, b});
        }
    return Mesh(std::move(positions), std::move(normals), std::move(indices));
}

Mesh cylinderMesh(double radius, double height)
{
    constexpr int kSegments = 32;
    MeshBuilder m;
    const double y0 = -0.5 * height, y1 = 0.5 * height;
    for (int k = 0; k < kSegments; ++k) {
        const dvec3 a0 = onRim(k, kSegments, radius, y0), b0 = onRim(k + 1, kSegments, radius, y0);
        const dvec3 a1 = onRim(k, kSegments, radius, y1), b1 = onRim(k + 1, kSegments, radius, y1);
        const dvec3 na = glm::normalize(dvec3(a0.x, 0.0, a0.z)), nb = glm::normalize(dvec3(b0.x, 0.0, b0.z));
        m.vertex(a0, na), m.vertex(a1, na), m.vertex(b1, nb);
        m.vertex(a0, na), m.vertex(b1, nb), m.vertex(b0, nb);
        m.flatTriangle(dvec3(0.0, y1, 0.0), b1, a1);
        m.flatTriangle(dvec3(0.0, y0, 0.0), a0, b0);
    }
    return m.take();
}

} // namespace

Mesh drawMeshOf(const Shape& shape)
{
    switch (shape.type) {
    case ShapeType::Box: return boxMesh(shape.size);
    case ShapeType::Sphere: return sphereMesh(shape.radius);
    case ShapeType::Cylinder: return cylinderMesh(shape.radius, shape.height);
    case ShapeType::Mesh: {
        MeshBuilder m;
        for (std::size_t t = 0; t + 2 < shape.triangles.size(); t += 3)
            m.flatTriangle(shape.vertices[shape.triangles[t]], shape.vertices[shape.triangles[t + 1]],
                           shape.vertices[shape.triangles[t + 2]]);
        return m.take();
    }
    }
    return {};
}

} // namespace pba
