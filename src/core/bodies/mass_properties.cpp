#include "pba/mass_properties.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace pba {

namespace {

void requirePositive(double value, const char* what)
{
    if (!(value > 0.0 && std::isfinite(value)))
        throw std::invalid_argument(fmt::format("a shape's {} must be finite and positive, got {}", what, value));
}

dmat3 diagonal(double x, double y, double z) { return dmat3(dvec3(x, 0.0, 0.0), dvec3(0.0, y, 0.0), dvec3(0.0, 0.0, z)); }

/// Eberly's subexpressions of one coordinate over a triangle's three vertices: the sums that
/// the integrals of 1, w, w^2 and w^3 over the triangle's projection reduce to.
struct Sums {
    double f1, f2, f3, g0, g1, g2;
};

Sums sums(double w0, double w1, double w2)
{
    const double t0 = w0 + w1;
    const double t1 = w0 * w0;
    const double t2 = t1 + w1 * t0;
    Sums s{};
    s.f1 = t0 + w2;
    s.f2 = t2 + w2 * s.f1;
    s.f3 = w0 * t1 + w1 * t2 + w2 * s.f2;
    s.g0 = s.f2 + w0 * (s.f1 + w0);
    s.g1 = s.f2 + w1 * (s.f1 + w1);
    s.g2 = s.f2 + w2 * (s.f1 + w2);
    return s;
}

/// Every edge of a closed, consistently oriented mesh is walked once each way. The directed edges
/// are sorted as 64-bit keys (from, to) rather than counted in a map: a mesh of millions of
/// triangles is checked in a sort, not in millions of allocations.
void requireClosed(std::span<const std::uint32_t> triangles)
{
    const auto key = [](std::uint32_t from, std::uint32_t to) { return std::uint64_t(from) << 32 | to; };
    std::vector<std::uint64_t> edges;
    edges.reserve(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); t += 3)
        for (std::size_t k = 0; k < 3; ++k)
            edges.push_back(key(triangles[t + k], triangles[t + (k + 1) % 3]));
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size(); ++i) {
        const std::uint64_t edge = edges[i];
        const auto from = std::uint32_t(edge >> 32), to = std::uint32_t(edge);
        const bool once = (i == 0 || edges[i - 1] != edge) && (i + 1 == edges.size() || edges[i + 1] != edge);
        const auto back = std::equal_range(edges.begin(), edges.end(), key(to, from));
        if (!once || back.second - back.first != 1)
            throw std::invalid_argument(fmt::format(
                "the mesh is not closed: its edge from vertex {} to vertex {} is not shared by exactly two "
                "triangles in opposite directions",
                from, to));
    }
}

} // namespace

MassProperties MassProperties::withMass(double newMass) const
{
    requirePositive(newMass, "mass");
    const double scale = newMass / mass;
    return {newMass, centre, inertia * scale};
}

MassProperties boxMassProperties(const dvec3& size, double density)
{
    requirePositive(size.x, "size");
    requirePositive(size.y, "size");
    requirePositive(size.z, "size");
    requirePositive(density, "density");
    const double m = density * size.x * size.y * size.z;
    const dvec3 s2 = size * size;
    return {m, dvec3(0.0), diagonal(m * (s2.y + s2.z) / 12.0, m * (s2.x + s2.z) / 12.0, m * (s2.x + s2.y) / 12.0)};
}

MassProperties sphereMassProperties(double radius, double density)
{
    requirePositive(radius, "radius");
    requirePositive(density, "density");
    const double m = density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
    const double i = 0.4 * m * radius * radius;
    return {m, dvec3(0.0), diagonal(i, i, i)};
}

MassProperties cylinderMassProperties(double radius, double height, double density)
{
    requirePositive(radius, "radius");
    requirePositive(height, "height");
    requirePositive(density, "density");
    const double m = density * std::numbers::pi * radius * radius * height;
    const double across = m * (3.0 * radius * radius + height * height) / 12.0;
    return {m, dvec3(0.0), diagonal(across, 0.5 * m * radius * radius, across)};
}

MassProperties meshMassProperties(std::span<const dvec3> vertices, std::span<const std::uint32_t> triangles,
                                  double density)
{
    requirePositive(density, "density");
    if (triangles.empty() || triangles.size() % 3 != 0)
        throw std::invalid_argument(
            fmt::format("a mesh needs whole triangles, three indices each: got {} indices", triangles.size()));
    for (const std::uint32_t index : triangles)
        if (index >= vertices.size())
            throw std::invalid_argument(
                fmt::format("a triangle names vertex {}, but the mesh has {} vertices", index, vertices.size()));
    requireClosed(triangles);
    // The integrals over the volume of 1, x, y, z, x^2, y^2, z^2, xy, yz and zx.
    std::array<double, 10> integral{};
    for (std::size_t t = 0; t < triangles.size(); t += 3) {
        const dvec3& p0 = vertices[triangles[t]];
        const dvec3& p1 = vertices[triangles[t + 1]];
        const dvec3& p2 = vertices[triangles[t + 2]];
        const dvec3 d = glm::cross(p1 - p0, p2 - p0); // twice the area along the outward normal
        const Sums x = sums(p0.x, p1.x, p2.x);
        const Sums y = sums(p0.y, p1.y, p2.y);
        const Sums z = sums(p0.z, p1.z, p2.z);
        integral[0] += d.x * x.f1;
        integral[1] += d.x * x.f2;
        integral[2] += d.y * y.f2;
        integral[3] += d.z * z.f2;
        integral[4] += d.x * x.f3;
        integral[5] += d.y * y.f3;
        integral[6] += d.z * z.f3;
        integral[7] += d.x * (p0.y * x.g0 + p1.y * x.g1 + p2.y * x.g2);
        integral[8] += d.y * (p0.z * y.g0 + p1.z * y.g1 + p2.z * y.g2);
        integral[9] += d.z * (p0.x * z.g0 + p1.x * z.g1 + p2.x * z.g2);
    }
    constexpr std::array<double, 10> kFactor{1.0 / 6,   1.0 / 24,  1.0 / 24,  1.0 / 24,  1.0 / 60,
                                             1.0 / 60,  1.0 / 60,  1.0 / 120, 1.0 / 120, 1.0 / 120};
    for (std::size_t k = 0; k < integral.size(); ++k)
        integral[k] *= kFactor[k] * density;
    const double m = integral[0];
    if (!std::isfinite(m))
        throw std::invalid_argument(fmt::format("the mesh is too large: its mass at {} kg/m^3 is not finite", density));
    if (m == 0.0)
        throw std::invalid_argument(fmt::format(
            "the mesh's mass at {} kg/m^3 is 0: it is flat, or too small for its volume to be represented", density));
    if (!(m > 0.0))
        throw std::invalid_argument(fmt::format(
            "the mesh's volume is {} (its triangles must turn counter-clockwise seen from outside)", m / density));
    const dvec3 c = dvec3(integral[1], integral[2], integral[3]) / m;
    // About the centre of mass (the parallel axis theorem taken off the origin's integrals).
    const double xx = integral[4] - m * c.x * c.x;
    const double yy = integral[5] - m * c.y * c.y;
    const double zz = integral[6] - m * c.z * c.z;
    const double xy = integral[7] - m * c.x * c.y;
    const double yz = integral[8] - m * c.y * c.z;
    const double zx = integral[9] - m * c.z * c.x;
    dmat3 inertia(0.0);
    inertia[0][0] = yy + zz;
    inertia[1][1] = zz + xx;
    inertia[2][2] = xx + yy;
    inertia[0][1] = inertia[1][0] = -xy;
    inertia[1][2] = inertia[2][1] = -yz;
    inertia[0][2] = inertia[2][0] = -zx;
    return {m, c, inertia};
}

} // namespace pba
