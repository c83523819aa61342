#pragma once
// Collisions of a point with the planes that bound the world (a ground plane, or the
// six faces of the room). The region allowed to a body is the intersection of the
// planes' inner half-spaces.
//
// How a bounce is resolved changes what the integrator study shows, so the response
// is a named choice:
//  - Exact: find the time of impact tau of the body's own integrator path, step to it,
//    reflect the normal velocity, and integrate the rest of the step. It adds no error
//    of its own: an integrator exact for constant acceleration stays exact through bounces.
//  - Reflect: the classic practical solution; after a full step, mirror a body found
//    beyond a surface back across it.
//  - Clamp: after a full step, put the body back on the surface.
// This header declares what a user of the library meets: the responses, the planes, and one
// body's step. The rules themselves are templates over the scalar type and the acceleration
// (one rule for a double-precision Particle and a float swarm) and live in src/core
// (collision_rules.hpp, and surface_tests.hpp for the swarm's batch tests), as Box2D keeps its
// public collision.h to declarations.
#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "pba/integrator.hpp"

namespace pba {

enum class CollisionResponse { Exact, Reflect, Clamp };

inline constexpr std::array<CollisionResponse, 3> kAllCollisionResponses{
    CollisionResponse::Exact, CollisionResponse::Reflect, CollisionResponse::Clamp};

/// "exact", "reflect", "clamp".
std::string_view collisionResponseName(CollisionResponse response);
std::optional<CollisionResponse> collisionResponseFromName(std::string_view name);
/// Every name collisionResponseFromName takes, as an error lists them: "exact, reflect or clamp".
std::string collisionResponseNameList();
/// One line for people: what the response does, and what it does to an elastic bounce.
std::string_view collisionResponseSummary(CollisionResponse response);

/// The half-space dot(normal, x) >= offset; `normal` is a unit vector pointing inside.
/// A plane may have a round hole (the blow dryer's, in the floor): a body crossing the plane
/// within holeRadius of holeCentre passes through, into a short shaft closed below by
/// another plane (the dryer's grille), and is kept inside the shaft's radius. Its members stay
/// inline here: the swarm's loops and a Particle's rule call them for every point, every step.
template <class T>
struct PlaneT {
    Vec3<T> normal;
    T offset;
    T holeRadius = T(0);
    Vec3<T> holeCentre{T(0)};

    /// A vector in the plane (see AxisPlaneT, which needs only two coordinates for one).
    using InPlane = Vec3<T>;

    T distance(const Vec3<T>& x) const { return glm::dot(normal, x) - offset; }
    /// The component of v along the normal, and x moved by s along it.
    T along(const Vec3<T>& v) const { return glm::dot(normal, v); }
    void moveAlong(Vec3<T>& x, T s) const { x += s * normal; }
    /// The offset of x from the hole's axis, in the plane.
    InPlane fromHoleAxis(const Vec3<T>& x) const
    {
        const Vec3<T> rel = x - holeCentre;
        return rel - glm::dot(rel, normal) * normal;
    }
    /// The component of v along a direction in the plane, and x moved by a vector in it.
    T alongInPlane(const Vec3<T>& v, const InPlane& direction) const { return glm::dot(v, direction); }
    void moveInPlane(Vec3<T>& x, const InPlane& d) const { x += d; }
    /// 0, 1 or 2 when the normal is exactly plus or minus that axis (a wall of a box), else -1.
    int axis() const
    {
        for (int i = 0; i < 3; ++i)
            if (std::abs(normal[i]) == T(1) && normal[(i + 1) % 3] == T(0) && normal[(i + 2) % 3] == T(0))
                return i;
        return -1;
    }
    /// The plane a ball of radius r meets with its centre: moved inward by r, its hole narrowed by r
    /// (a ball passes only where all of it fits; none where it does not fit at all).
    PlaneT inflatedBy(T r) const
    {
        const T hole = holeRadius - r;
        return {normal, offset + r, hole > T(0) ? hole : T(0), holeCentre};
    }
    bool overHole(const Vec3<T>& x) const
    {
        const Vec3<T> rho = fromHoleAxis(x);
        return holeRadius > T(0) && glm::dot(rho, rho) < holeRadius * holeRadius;
    }
};
using Plane = PlaneT<double>;

/// One step of a point body from (x, v) by dt with `integrator` under the acceleration
/// accel(x, v), bounded by `planes` with the chosen response and coefficient of restitution;
/// returns the number of bounces. (The World steps its bodies with the same rule, inlined.)
int stepWithCollisions(CollisionResponse response, Integrator integrator, std::span<const Plane> planes,
                       double restitution, dvec3& x, dvec3& v, double dt,
                       const std::function<dvec3(const dvec3&, const dvec3&)>& accel);

/// The planes of a ground at height h (y up).
template <class T>
inline std::array<PlaneT<T>, 1> groundPlanes(T height)
{
    return {PlaneT<T>{Vec3<T>(0, 1, 0), height}};
}

/// The six inward-facing planes of an axis-aligned room; the floor comes first.
template <class T>
inline std::array<PlaneT<T>, 6> roomPlanes(const Vec3<T>& lo, const Vec3<T>& hi)
{
    return {PlaneT<T>{Vec3<T>(0, 1, 0), lo.y},  PlaneT<T>{Vec3<T>(0, -1, 0), -hi.y},
            PlaneT<T>{Vec3<T>(1, 0, 0), lo.x},  PlaneT<T>{Vec3<T>(-1, 0, 0), -hi.x},
            PlaneT<T>{Vec3<T>(0, 0, 1), lo.z},  PlaneT<T>{Vec3<T>(0, 0, -1), -hi.z}};
}

} // namespace pba
