#include "pba/overlap.hpp"

#include <algorithm>

#include "contact/narrow_phase.hpp"
#include "particle_grid.hpp"

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

} // namespace pba
