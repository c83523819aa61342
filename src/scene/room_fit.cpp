#include "room_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "one_line.hpp"
#include "pba/overlap.hpp"
#include "pba/scene/scene.hpp"

namespace pba::scene_detail {

namespace {

/// A gap this small against the numbers involved is touching: a turned box's corner computed on
/// the floor lands a rounding error either side of it.
constexpr double kTouch = 1e-9;
/// How deep a body may start in another: a millimetre's push is not seen (a box set on a ramp
/// by hand is that close to it).
constexpr double kInsideTolerance = 1e-3;
/// A cylinder's rims as polygons of this many corners, where a shape is cut by the floor over
/// the hole (the polygon falls short of the circle by 1 - cos(pi / 256), under 1e-4 of the radius).
constexpr int kRimCorners = 256;

/// A rigid body's shape at its pose.
struct PlacedShape {
    const Shape& shape;
    dmat3 turn;  ///< body frame to world frame
    dvec3 centre; ///< the centre of mass, world frame
};

/// How far the shape reaches from its centre along the unit vector d: the largest d . p over
/// its points p (its support function), exact for every shape.
double reach(const PlacedShape& s, const dvec3& d)
{
    const Shape& shape = s.shape;
    switch (shape.type) {
    case ShapeType::Box: {
        double sum = 0.0;
        for (int i = 0; i < 3; ++i)
            sum += std::abs(glm::dot(d, s.turn[i])) * 0.5 * shape.size[i];
        return sum;
    }
    case ShapeType::Sphere: return shape.radius;
    case ShapeType::Cylinder: { // its axis is the body's y; a rim reaches r sin(angle to the axis)
        const double c = glm::dot(d, s.turn[1]);
        return 0.5 * shape.height * std::abs(c) + shape.radius * std::sqrt(std::max(0.0, 1.0 - c * c));
    }
    case ShapeType::Mesh: {
        double most = -std::numeric_limits<double>::infinity();
        for (const dvec3& v : shape.vertices)
            most = std::max(most, glm::dot(d, s.turn * v));
        return most;
    }
    }
    return 0.0;
}

/// The shape as corners (world frame) and the edges between them: a box's, a mesh's, or a
/// cylinder's rims as polygons joined by its side.
struct Outline {
    std::vector<dvec3> corners;
    std::vector<std::pair<std::size_t, std::size_t>> edges;
};

Outline outlineOf(const PlacedShape& s)
{
    Outline o;
    const Shape& shape = s.shape;
    if (shape.type == ShapeType::Box) {
        for (const dvec3& corner : contactPointsOf(shape)) // corner k has the signs of k's bits
            o.corners.push_back(s.centre + s.turn * corner);
        for (std::size_t k = 0; k < 8; ++k)
            for (const std::size_t bit : {1u, 2u, 4u})
                if (!(k & bit))
                    o.edges.emplace_back(k, k | bit);
    } else if (shape.type == ShapeType::Mesh) {
        for (const dvec3& v : shape.vertices)
            o.corners.push_back(s.centre + s.turn * v);
        for (std::size_t t = 0; t + 2 < shape.triangles.size(); t += 3)
            for (int e = 0; e < 3; ++e)
                o.edges.emplace_back(shape.triangles[t + e], shape.triangles[t + (e + 1) % 3]);
    } else if (shape.type == ShapeType::Cylinder) {
        const std::size_t n = kRimCorners;
        for (const double y : {-0.5 * shape.height, 0.5 * shape.height})
            for (std::size_t k = 0; k < n; ++k) {
                const double angle = 2.0 * std::numbers::pi * double(k) / double(n);
                o.corners.push_back(s.centre +
                                    s.turn * dvec3(shape.radius * std::cos(angle), y, shape.radius * std::sin(angle)));
            }
        for (std::size_t k = 0; k < n; ++k)
            o.edges.insert(o.edges.end(), {{k, (k + 1) % n}, {n + k, n + (k + 1) % n}, {k, n + k}});
    }
    return o;
}

/// The farthest the part of the shape beyond `plane` (the floor) lies from the hole's axis.
/// Convex pieces reach farthest at a corner: a corner beyond the plane, or where an edge
/// crosses it.
double farthestBeyond(const PlacedShape& s, const Plane& plane)
{
    if (s.shape.type == ShapeType::Sphere) {
        const double d = plane.distance(s.centre), r = s.shape.radius;
        return glm::length(plane.fromHoleAxis(s.centre)) + (d >= 0.0 ? std::sqrt(std::max(0.0, r * r - d * d)) : r);
    }
    const Outline o = outlineOf(s);
    double farthest = 0.0;
    const auto consider = [&](const dvec3& x) { farthest = std::max(farthest, glm::length(plane.fromHoleAxis(x))); };
    for (const dvec3& x : o.corners)
        if (plane.distance(x) < 0.0)
            consider(x);
    for (const auto& [a, b] : o.edges) {
        const double da = plane.distance(o.corners[a]), db = plane.distance(o.corners[b]);
        if ((da < 0.0) != (db < 0.0))
            consider(o.corners[a] + (da / (da - db)) * (o.corners[b] - o.corners[a]));
    }
    return farthest;
}

/// "the floor (y = 0)", "the wall at x = -2", "the grille (y = -0.05)".
std::string surfaceName(const World& world, const Plane& plane)
{
    const int axis = plane.axis();
    if (axis < 0)
        return "a surface";
    const double at = plane.offset * plane.normal[axis]; // the normal is plus or minus that axis
    if (axis != 1)
        return fmt::format("the wall at {} = {:g}", "xyz"[axis], at);
    if (plane.normal.y < 0.0)
        return fmt::format("the ceiling (y = {:g})", at);
    // With a hole, the floor is the plane that carries it, and the other facing up is the grille.
    if (world.floorHole() && plane.holeRadius == 0.0)
        return fmt::format("the grille under the floor's hole (y = {:g})", at);
    return fmt::format("the {} (y = {:g})", world.ground() ? "ground" : "floor", at);
}

/// The first surface the shape reaches through, and how deep; none when it is clear of all.
std::optional<std::pair<std::string, double>> firstOverlap(const World& world, const PlacedShape& s, double scale)
{
    for (const Plane& plane : world.planes()) {
        const double touch = kTouch * (scale + std::abs(plane.offset) + plane.holeRadius);
        const double gap = plane.distance(s.centre) - reach(s, -plane.normal);
        if (gap >= -touch)
            continue;
        if (plane.holeRadius > 0.0) { // below the floor only within the hole
            if (farthestBeyond(s, plane) <= plane.holeRadius + touch)
                continue;
            return std::pair{surfaceName(world, plane) + " outside its hole", -gap};
        }
        return std::pair{surfaceName(world, plane), -gap};
    }
    return std::nullopt;
}

/// Why the shape, at its orientation, cannot fit in the room along some axis; none if it can.
std::optional<std::string> tooLarge(const World& world, const PlacedShape& s, double scale)
{
    if (!world.room())
        return std::nullopt;
    for (int i = 0; i < 3; ++i) {
        dvec3 axis(0.0);
        axis[i] = 1.0;
        const double span = reach(s, axis) + reach(s, -axis), room = world.room()->max[i] - world.room()->min[i];
        if (span > room + kTouch * (scale + room))
            return fmt::format("at its orientation the {} spans {:.3g} m along {}, more than the room's {:.3g} m: it "
                               "cannot fit in the room", shapeTypeName(s.shape.type), span, "xyz"[i], room);
    }
    return std::nullopt;
}

} // namespace

void requireRigidBodiesInside(const World& world, const std::string& file)
{
    std::size_t k = 0;
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        if (!world.isRigid(i))
            continue;
        const auto& body = static_cast<const RigidBody&>(world.body(i));
        const PlacedShape s{body.getShape(), glm::mat3_cast(body.getOrientation()), body.getPos()};
        const std::string key = fmt::format("rigid_bodies[{}]", k++);
        const double scale = 1.0 + glm::length(s.centre) + body.getBoundingRadius();
        const auto overlap = firstOverlap(world, s, scale);
        if (!overlap)
            continue;
        if (const auto why = tooLarge(world, s, scale))
            throw SceneError(file, key + ".shape", *why);
        const bool turns = s.shape.type != ShapeType::Sphere;
        throw SceneError(file, key + ".position",
                         fmt::format("the {}{} reaches {:.3g} m through {}: a body must start {} (touching a surface "
                                     "is allowed)", shapeTypeName(s.shape.type), turns ? " at its orientation" : "",
                                     overlap->second, overlap->first,
                                     world.room() ? "inside the room" : "above the ground"));
    }
}

void requireRigidBodiesApart(const World& world, const std::string& file, const std::vector<BodyPair>& joinedApart)
{
    // Bounding spheres swept along x: a pile of dice in a scene file meets only its neighbours.
    struct Reach {
        double low, high;
        std::size_t body, index; ///< world index; index among the rigid bodies (rigid_bodies[index])
    };
    std::vector<Reach> reaches;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (world.isRigid(i)) {
            const auto& body = static_cast<const RigidBody&>(world.body(i));
            const double r = body.getBoundingRadius();
            reaches.push_back({body.getPos().x - r, body.getPos().x + r, i, reaches.size()});
        }
    std::sort(reaches.begin(), reaches.end(), [](const Reach& a, const Reach& b) { return a.low < b.low; });
    // The deepest of the first body (in the file's order) that starts inside another.
    std::optional<std::pair<const Reach*, const Reach*>> first;
    double firstDepth = 0.0;
    for (std::size_t k = 0; k < reaches.size(); ++k)
        for (std::size_t j = k + 1; j < reaches.size() && reaches[j].low <= reaches[k].high; ++j) {
            const auto& a = static_cast<const RigidBody&>(world.body(reaches[k].body));
            const auto& b = static_cast<const RigidBody&>(world.body(reaches[j].body));
            const BodyPair key{std::min(reaches[k].body, reaches[j].body), std::max(reaches[k].body, reaches[j].body)};
            if ((a.isFixed() && b.isFixed()) || std::binary_search(joinedApart.begin(), joinedApart.end(), key))
                continue;
            const double depth = overlapDepth(a, b);
            if (depth <= kInsideTolerance)
                continue;
            // The moving one is named; of two moving ones, the later in the file.
            const Reach* named = &reaches[k];
            const Reach* other = &reaches[j];
            if (a.isFixed() || (!b.isFixed() && reaches[j].index > reaches[k].index))
                std::swap(named, other);
            if (!first || named->index < first->first->index ||
                (named->index == first->first->index && depth > firstDepth)) {
                first.emplace(named, other);
                firstDepth = depth;
            }
        }
    if (!first)
        return;
    const auto& body = static_cast<const RigidBody&>(world.body(first->first->body));
    const auto& other = static_cast<const RigidBody&>(world.body(first->second->body));
    const bool turns = body.getShape().type != ShapeType::Sphere;
    throw SceneError(file, fmt::format("rigid_bodies[{}].position", first->first->index),
                     fmt::format("the {}{} starts {:.3g} m inside the {}body '{}': {}", shapeTypeName(body.getShape().type),
                                 turns ? " at its orientation" : "", firstDepth, other.isFixed() ? "fixed " : "",
                                 oneLine(other.getName()),
                                 other.isFixed() ? "a body must start outside every fixed body (touching is allowed)"
                                                 : "bodies that collide must start apart (touching is allowed; "
                                                   "joined ones collide only with \"collide\": true)"));
}

namespace {

/// Where a particle comes from in the file: particles[i], or its rope's or cloth's entry.
std::string particleKey(const World& world, const FabricLayout& fabric, std::size_t body)
{
    for (std::size_t k = 0; k < fabric.ropes.size(); ++k)
        if (std::ranges::find(fabric.ropes[k].particles, body) != fabric.ropes[k].particles.end())
            return fmt::format("ropes[{}]", k);
    for (std::size_t k = 0; k < fabric.cloths.size(); ++k) {
        const ClothLayout& c = fabric.cloths[k];
        if (body >= c.first && body < c.first + c.width * c.height)
            return fmt::format("cloths[{}]", k);
    }
    std::size_t loose = 0; // the particles' entries come first, in order
    for (std::size_t i = 0; i < body; ++i)
        loose += !world.isRigid(i) ? 1 : 0;
    return fmt::format("particles[{}].position", loose);
}

} // namespace

void requireParticlesOutsideRigidBodies(const World& world, const FabricLayout& fabric, const std::string& file,
                                        const std::vector<BodyPair>& joinedApart)
{
    // A ball started inside a body is pushed out through its nearest face in a step or two, with
    // the energy of the push: a rope strung through a box gained 7 times its energy in a second.
    std::vector<std::size_t> rigid;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (world.isRigid(i))
            rigid.push_back(i);
    for (std::size_t i = 0; i < world.bodyCount() && !rigid.empty(); ++i) {
        const auto* particle = dynamic_cast<const Particle*>(&world.body(i));
        if (!particle || particle->getRadius() <= 0.0)
            continue;
        for (const std::size_t k : rigid) {
            const auto& body = static_cast<const RigidBody&>(world.body(k));
            const BodyPair key{std::min(i, k), std::max(i, k)};
            if ((particle->isFixed() && body.isFixed()) ||
                std::binary_search(joinedApart.begin(), joinedApart.end(), key))
                continue;
            const double depth = overlapDepth(body, particle->getPos(), particle->getRadius());
            if (depth <= kInsideTolerance)
                continue;
            throw SceneError(file, particleKey(world, fabric, i),
                             fmt::format("the particle '{}' (radius {:g} m) starts {:.3g} m inside the {}body '{}': a "
                                         "particle with a radius must start outside every rigid body (touching is "
                                         "allowed; one joined to the body with a joint may start inside it)",
                                         oneLine(particle->getName()), particle->getRadius(), depth,
                                         body.isFixed() ? "fixed " : "", oneLine(body.getName())));
        }
    }
}

} // namespace pba::scene_detail
