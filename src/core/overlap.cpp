#include "pba/overlap.hpp"

#include <algorithm>

#include "contact/narrow_phase.hpp"
#include "balls/particle_grid.hpp"

namespace pba {

double overlapDepth(const RigidBody& a, const RigidBody& b)
{
    if (glm::length(b.getPos() - a.getPos()) > a.getBoundingRadius() + b.getBoundingRadius())
        return 0.0;
    const auto transform = [](const RigidBody& body) {
        return contact::Transform{body.getPos(), glm::mat3_cast(body.getOrientation())};
    };
    const contact::Manifold m = contact::collide(contact::CollisionShape::of(a.getShape()), transform(a),
                                                 contact::CollisionShape::of(b.getShape()), transform(b), 0.0);
    double depth = 0.0;
    for (int i = 0; i < m.count; ++i)
        depth = std::max(depth, -m.points[std::size_t(i)].separation);
    return depth;
}

double overlapDepth(const RigidBody& body, const dvec3& centre, double radius)
{
    if (glm::length(centre - body.getPos()) > body.getBoundingRadius() + radius)
        return 0.0;
    const contact::Manifold m =
        contact::collide(contact::CollisionShape::of(body.getShape()),
                         contact::Transform{body.getPos(), glm::mat3_cast(body.getOrientation())},
                         contact::CollisionShape::of(Shape::sphere(radius)), contact::Transform{centre, dmat3(1.0)}, 0.0);
    double depth = 0.0;
    for (int i = 0; i < m.count; ++i)
        depth = std::max(depth, -m.points[std::size_t(i)].separation);
    return depth;
}

double overlapDepth(const RigidBody& body, const dvec3& a, double ra, const dvec3& b, double rb, int pieces)
{
    const double length = glm::length(b - a), gap = length - ra - rb;
    if (!(gap > 0.0) || glm::length(0.5 * (a + b) - body.getPos()) > body.getBoundingRadius() + 0.5 * length + ra + rb)
        return 0.0;
    const contact::CollisionShape& shape = *body.getCollisionShape(); // built once with the body
    const contact::Transform pose{body.getPos(), glm::mat3_cast(body.getOrientation())};
    double depth = 0.0;
    for (int k = 1; k < pieces; ++k) {
        const double t = double(k) / pieces;
        const double radius = std::min(ra + t * (rb - ra), 0.5 * gap);
        const contact::Manifold m = contact::collide(shape, pose, contact::CollisionShape::of(Shape::sphere(radius)),
                                                     contact::Transform{a + t * (b - a), dmat3(1.0)}, 0.0);
        for (int i = 0; i < m.count; ++i)
            depth = std::max(depth, -m.points[std::size_t(i)].separation);
    }
    return depth;
}

double halfSmallestGap(const std::array<dvec3, 3>& x, const std::array<double, 3>& r)
{
    double half = INFINITY;
    for (std::size_t e = 0; e < 3; ++e) {
        const std::size_t f = (e + 1) % 3;
        const double gap = glm::length(x[f] - x[e]) - r[e] - r[f];
        if (!(gap > 0.0))
            return 0.0;
        half = std::min(half, 0.5 * gap);
    }
    return half;
}

double overlapDepth(const RigidBody& body, const std::array<dvec3, 3>& x, const std::array<double, 3>& r)
{
    const double thickest = halfSmallestGap(x, r);
    if (!(thickest > 0.0))
        return 0.0;
    const dvec3 e1 = x[1] - x[0], e2 = x[2] - x[0];
    const dvec3 across = glm::cross(e1, e2);
    const double twiceArea = glm::length(across);
    if (!(twiceArea > 0.0))
        return 0.0;
    const dvec3 n = across / twiceArea;
    // Away from the side the body's centre is on.
    const dvec3 away = glm::dot(body.getPos() - x[0], n) > 0.0 ? -n : n;
    if (glm::dot(body.getPos() - x[0], -away) > body.getBoundingRadius() + thickest)
        return 0.0;
    double depth = 0.0;
    const auto look = [&](const dvec3& p) {
        const dvec3 q = p - x[0];
        const double u = glm::dot(glm::cross(q, e2), n) / twiceArea, v = glm::dot(glm::cross(e1, q), n) / twiceArea;
        if (!(u > 0.0 && v > 0.0 && u + v < 1.0))
            return;
        const double thickness = std::min((1.0 - u - v) * r[0] + u * r[1] + v * r[2], thickest);
        // Within the triangle's thickness: a point further through lies beyond its plane beside
        // it (a half-cell tilted over a box's edge has the box's far corner over it).
        if (const double through = glm::dot(q, away); through < thickness)
            depth = std::max(depth, through + thickness);
    };
    const contact::CollisionShape& shape = *body.getCollisionShape();
    if (shape.kind == contact::CollisionShape::Kind::Sphere)
        look(body.getPos() + shape.radius * away);
    else
        for (const dvec3& vertex : shape.polyhedron->vertices)
            look(body.getPos() + glm::mat3_cast(body.getOrientation()) * vertex);
    return depth;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> nearBallPairs(std::span<const dvec3> centres,
                                                                   std::span<const double> radii, double gap)
{
    // Each ball grown by half the gap: two are then "touching" when their surfaces are within it.
    const auto reach = [&](std::size_t i) { return radii[i] + 0.5 * gap; };
    double largest = 0.0;
    for (std::size_t i = 0; i < radii.size(); ++i)
        largest = std::max(largest, reach(i));
    detail::ParticleGrid grid;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    grid.findPairs(centres.size(), [&](std::size_t i) { return centres[i]; }, reach, largest, pairs);
    return pairs;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> ballsInSpheres(std::span<const dvec3> centres,
                                                                    std::span<const double> radii,
                                                                    std::span<const dvec3> around,
                                                                    std::span<const double> reach)
{
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    if (around.empty())
        return pairs;
    const auto at = [&](std::size_t j) { return around[j]; };
    const auto size = [&](std::size_t j) { return reach[j]; };
    detail::ParticleGrid grid;
    grid.build(around.size(), at, size, *std::max_element(reach.begin(), reach.end()));
    std::vector<std::uint32_t> near;
    for (std::size_t i = 0; i < centres.size(); ++i) {
        grid.near(centres[i], radii[i], at, size, near);
        for (const std::uint32_t j : near)
            pairs.emplace_back(std::uint32_t(i), j);
    }
    return pairs;
}

} // namespace pba
