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
// Every function here is a template over the scalar type and the acceleration, so the
// same rule serves a double-precision Particle and a float swarm.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <utility>

#include "pba/integrator.hpp"

namespace pba {

enum class CollisionResponse { Exact, Reflect, Clamp };

inline constexpr std::array<CollisionResponse, 3> kAllCollisionResponses{
    CollisionResponse::Exact, CollisionResponse::Reflect, CollisionResponse::Clamp};

/// "exact", "reflect", "clamp".
std::string_view collisionResponseName(CollisionResponse response);
std::optional<CollisionResponse> collisionResponseFromName(std::string_view name);
/// One line for people: what the response does, and what it does to an elastic bounce.
std::string_view collisionResponseSummary(CollisionResponse response);

/// The half-space dot(normal, x) >= offset; `normal` is a unit vector pointing inside.
/// A plane may have a round hole (the blow dryer's, in the floor): a body crossing the plane
/// within holeRadius of holeCentre passes through, into a short shaft closed below by
/// another plane (the dryer's grille), and is kept inside the shaft's radius.
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
    bool overHole(const Vec3<T>& x) const
    {
        const Vec3<T> rho = fromHoleAxis(x);
        return holeRadius > T(0) && glm::dot(rho, rho) < holeRadius * holeRadius;
    }
};
using Plane = PlaneT<double>;

/// A plane whose normal is plus or minus coordinate axis kAxis (a wall, the floor or the
/// ceiling of a room), with the axis known when the code is compiled: the same geometry as
/// PlaneT, without the arithmetic of the normal's two zero components. The collision rule below
/// is written once, over the primitives both provide; a swarm's passes hand it this form for
/// the walls of its room, where the generic form did three times the arithmetic a particle
/// (the floor with the blow dryer's hole was a third of a settled swarm's step). For finite
/// coordinates it does what PlaneT does, rounding for rounding (tested; only the sign of a zero
/// may differ), but for where a compiler fuses a product into a sum, which is its choice for
/// each form.
template <class T, int kAxis>
struct AxisPlaneT {
    static_assert(kAxis >= 0 && kAxis < 3);
    /// The in-plane axes, in the order PlaneT's vectors hold them (so sums round alike).
    static constexpr int kU = kAxis == 0 ? 1 : 0, kV = kAxis == 2 ? 1 : 2;
    using InPlane = glm::vec<2, T, glm::defaultp>; ///< coordinates kU and kV

    T sign; ///< the normal's component on kAxis: 1 or -1
    T offset;
    T holeRadius;
    InPlane holeCentre; ///< the hole's centre, coordinates kU and kV

    /// `plane` must have plane.axis() == kAxis.
    explicit AxisPlaneT(const PlaneT<T>& plane)
        : sign(plane.normal[kAxis]), offset(plane.offset), holeRadius(plane.holeRadius),
          holeCentre(plane.holeCentre[kU], plane.holeCentre[kV])
    {
    }
    T distance(const Vec3<T>& x) const { return sign * x[kAxis] - offset; }
    T along(const Vec3<T>& v) const { return sign * v[kAxis]; }
    void moveAlong(Vec3<T>& x, T s) const { x[kAxis] += s * sign; }
    InPlane fromHoleAxis(const Vec3<T>& x) const { return InPlane(x[kU], x[kV]) - holeCentre; }
    T alongInPlane(const Vec3<T>& v, const InPlane& direction) const
    {
        return glm::dot(InPlane(v[kU], v[kV]), direction);
    }
    void moveInPlane(Vec3<T>& x, const InPlane& d) const
    {
        x[kU] += d.x;
        x[kV] += d.y;
    }
};

/// Calls f(plane) with the plane as an AxisPlaneT when its normal is a coordinate axis, as
/// itself otherwise: f is compiled for each form, and the call picks one per plane.
template <class T, class F>
inline decltype(auto) withPlaneGeometry(const PlaneT<T>& plane, F&& f)
{
    switch (plane.axis()) {
    case 0: return f(AxisPlaneT<T, 0>(plane));
    case 1: return f(AxisPlaneT<T, 1>(plane));
    case 2: return f(AxisPlaneT<T, 2>(plane));
    default: return f(plane);
    }
}

namespace collision_detail {

/// std::min by value, for the loops over a swarm's arrays: std::min takes and returns
/// references, and GCC 12 stopped vectorising lowerDepthInBox ("complicated access pattern")
/// when a change elsewhere in the step altered how it was inlined. The same result as std::min.
template <class T>
inline T lesser(T a, T b)
{
    return b < a ? b : a;
}

/// How many impacts one step may resolve before the rest of it is clamped (a body
/// wedged in a corner with e close to 1 would otherwise loop).
inline constexpr int kMaxEvents = 16;

template <class T>
inline T contactTolerance(const PlaneT<T>& plane)
{
    return T(64) * std::numeric_limits<T>::epsilon() * (T(1) + std::abs(plane.offset));
}

/// Moves x onto the plane along its normal (Sterbenz: exact when x is near the plane).
template <class T>
inline void snapOnto(const PlaneT<T>& plane, Vec3<T>& x)
{
    x -= plane.distance(x) * plane.normal;
}

/// Smallest tau in (0, limit] where c0 + c1 tau + c2 tau^2 falls through zero, with c0 >= 0.
/// Uses the cancellation-free form of the quadratic formula.
template <class T>
inline std::optional<T> firstQuadraticCrossing(T c0, T c1, T c2, T limit)
{
    if (c0 <= T(0) && c1 < T(0))
        return T(0); // on the surface and moving in: impact now
    std::optional<T> best;
    auto consider = [&](T r) {
        if (r > T(0) && r <= limit && (!best || r < *best))
            best = r;
    };
    if (c2 == T(0)) {
        if (c1 < T(0))
            consider(-c0 / c1);
        return best;
    }
    const T disc = c1 * c1 - T(4) * c2 * c0;
    if (disc < T(0))
        return best;
    const T q = T(-0.5) * (c1 + std::copysign(std::sqrt(disc), c1));
    if (q != T(0)) {
        consider(q / c2);
        consider(c0 / q);
    }
    // Only a crossing from inside to outside counts: the slope there must be negative.
    if (best && c1 + T(2) * c2 * *best > T(0))
        return std::nullopt;
    return best;
}

/// Signed distance after one integrator step of length tau from (x, v).
template <class T, class Accel>
inline T distanceAfter(Integrator integrator, const PlaneT<T>& plane, Vec3<T> x, Vec3<T> v, T tau, Accel&& accel)
{
    integrate(integrator, x, v, tau, accel);
    return plane.distance(x);
}

/// The time of impact of one integrator step with a plane, or nothing if the step stays inside.
/// Forward Euler, semi-implicit Euler and velocity Verlet move the position along a polynomial
/// in tau built from the start-of-step acceleration, so their impact time is closed form.
/// RK4's path is a polynomial only for constant forces: it is bracketed and bisected on the
/// real RK4 step, which converges to the same root (to rounding) when the forces are constant.
template <class T, class Accel>
inline std::optional<T> timeOfImpact(Integrator integrator, const PlaneT<T>& plane, const Vec3<T>& x,
                                     const Vec3<T>& v, T limit, Accel&& accel)
{
    const T c0 = std::max(plane.distance(x), T(0));
    const T c1 = glm::dot(plane.normal, v);
    const T an = glm::dot(plane.normal, accel(x, v));
    switch (integrator) {
    case Integrator::ForwardEuler: return firstQuadraticCrossing(c0, c1, T(0), limit);
    case Integrator::SemiImplicitEuler: return firstQuadraticCrossing(c0, c1, an, limit);
    case Integrator::VelocityVerlet: return firstQuadraticCrossing(c0, c1, T(0.5) * an, limit);
    case Integrator::RK4: break;
    }
    // RK4: the constant-acceleration estimate and a few samples find the first sign change.
    constexpr int kSamples = 8;
    const std::optional<T> estimate = firstQuadraticCrossing(c0, c1, T(0.5) * an, limit);
    if (estimate && *estimate == T(0))
        return estimate;
    if (!estimate && distanceAfter(integrator, plane, x, v, limit, accel) >= T(0))
        return std::nullopt;
    std::array<T, kSamples + 1> taus{};
    std::size_t count = 0;
    for (int k = 1; k <= kSamples; ++k)
        taus[count++] = limit * T(k) / T(kSamples);
    if (estimate)
        taus[count++] = *estimate;
    std::sort(taus.begin(), taus.begin() + count);
    T lo = T(0);
    T hi = limit;
    bool found = false;
    for (std::size_t i = 0; i < count && !found; ++i) {
        if (distanceAfter(integrator, plane, x, v, taus[i], accel) < T(0)) {
            hi = taus[i];
            found = true;
        } else {
            lo = taus[i];
        }
    }
    if (!found)
        return std::nullopt;
    for (int i = 0; i < 200 && lo < hi; ++i) {
        const T mid = lo + (hi - lo) * T(0.5);
        if (mid <= lo || mid >= hi)
            break;
        (distanceAfter(integrator, plane, x, v, mid, accel) < T(0) ? hi : lo) = mid;
    }
    return hi;
}

/// timeOfImpact for a plane that may have a hole: a body already in the shaft below the hole
/// does not meet the plane, and neither does one whose path crosses it over the hole.
template <class T, class Accel>
inline std::optional<T> timeOfImpactWithHole(Integrator integrator, const PlaneT<T>& plane, const Vec3<T>& x,
                                             const Vec3<T>& v, T limit, Accel&& accel)
{
    if (plane.holeRadius <= T(0))
        return timeOfImpact(integrator, plane, x, v, limit, accel);
    if (plane.distance(x) < T(0) && plane.overHole(x))
        return std::nullopt;
    const std::optional<T> tau = timeOfImpact(integrator, plane, x, v, limit, accel);
    if (!tau)
        return tau;
    Vec3<T> xi = x;
    Vec3<T> vi = v;
    integrate(integrator, xi, vi, *tau, accel);
    return plane.overHole(xi) ? std::nullopt : tau;
}

/// Puts a body in the shaft below a hole (`inShaft`) that is at or beyond the shaft's side wall
/// back just inside it, and reflects its outward radial velocity with restitution. Selects
/// rather than branches, as pushBack, so a swarm's vectorised pass runs it too: a body that is
/// not at the wall is left as it was. Returns whether it moved the body; counts the bounce.
/// `plane` is a PlaneT or an AxisPlaneT, as for every function of the rule below.
template <class Geometry, class T>
inline bool pushIntoShaft(const Geometry& plane, T restitution, bool inShaft, Vec3<T>& x, Vec3<T>& v, int& bounces)
{
    const auto rho = plane.fromHoleAxis(x);
    const T r = glm::length(rho);
    const bool atWall = inShaft & !(r < plane.holeRadius) & (r > T(0));
    const auto out = rho / (r > T(0) ? r : T(1)); // read only at the wall, where r > 0
    Vec3<T> pushed = x;
    plane.moveInPlane(pushed, -(r - plane.holeRadius * (T(1) - T(16) * std::numeric_limits<T>::epsilon())) * out);
    const T vr = plane.alongInPlane(v, out);
    const bool bounce = atWall & (vr > T(0));
    Vec3<T> reflected = v;
    plane.moveInPlane(reflected, -((T(1) + restitution) * vr) * out);
    // Whole selects, not x -= (atWall ? ... : 0) * out: away from the wall nothing changes, not
    // even the sign of a zero.
    x = Vec3<T>(atWall ? pushed.x : x.x, atWall ? pushed.y : x.y, atWall ? pushed.z : x.z);
    v = Vec3<T>(bounce ? reflected.x : v.x, bounce ? reflected.y : v.y, bounce ? reflected.z : v.z);
    bounces += int(bounce);
    return atWall;
}

/// Keeps a body that is in the shaft below a hole within the shaft's radius (pushIntoShaft).
template <class Geometry, class T>
inline int keepInShaft(const Geometry& plane, T restitution, Vec3<T>& x, Vec3<T>& v)
{
    int bounces = 0;
    pushIntoShaft(plane, restitution, true, x, v, bounces);
    return bounces;
}

/// Whether a body that ended the step at x, from `start`, is excused from `plane` by its hole:
/// it is over the hole, or it was already in the shaft below. Bitwise operators rather than
/// && and ||, so a swarm loop can evaluate it for every particle without branches.
template <class Geometry, class T>
inline bool throughHole(const Geometry& plane, const Vec3<T>& start, const Vec3<T>& x)
{
    const auto rho = plane.fromHoleAxis(x);
    return (plane.holeRadius > T(0)) &
           ((glm::dot(rho, rho) < plane.holeRadius * plane.holeRadius) | (plane.distance(start) < T(0)));
}

/// A body lies on a plane when it touches it and does not move away from it.
template <class T>
inline bool restsOn(const PlaneT<T>& plane, const Vec3<T>& x, const Vec3<T>& v)
{
    return std::abs(plane.distance(x)) <= contactTolerance(plane) && glm::dot(plane.normal, v) <= T(0) &&
           !plane.overHole(x);
}

/// Last line of defence for every mode: a body never ends a step outside. `start` is where
/// the step began: a body that was in a hole's shaft is kept in the shaft.
template <class T>
inline int keepInside(std::span<const PlaneT<T>> planes, T restitution, const Vec3<T>& start, Vec3<T>& x, Vec3<T>& v)
{
    int bounces = 0;
    for (const PlaneT<T>& plane : planes) {
        if (plane.distance(x) < T(0)) {
            if (throughHole(plane, start, x)) {
                bounces += keepInShaft(plane, restitution, x, v);
                continue;
            }
            snapOnto(plane, x);
            const T vn = glm::dot(plane.normal, v);
            if (vn < T(0))
                v -= vn * plane.normal;
        }
    }
    return bounces;
}

} // namespace collision_detail

/// The exact response. Returns the number of bounces during the step.
///
/// Resting contact: a body on a surface whose net acceleration pushes into it is held
/// there by removing the normal components of its velocity and acceleration (the
/// surface's normal force), so it neither sinks nor bounces an endless number of
/// zero-length times. With e < 1 a rebound too weak to leave the surface for one full
/// step (slower than |a.n| dt) becomes such a contact; with e = 1 no energy may be
/// lost, so every rebound is kept.
template <class T, class Accel>
inline int stepExact(Integrator integrator, std::span<const PlaneT<T>> planes, T restitution, Vec3<T>& x,
                     Vec3<T>& v, T dt, Accel&& accel)
{
    using namespace collision_detail;
    constexpr std::size_t kMaxPlanes = 8;
    std::array<bool, kMaxPlanes> contact{};
    auto constrained = [&](const Vec3<T>& px, const Vec3<T>& pv) {
        Vec3<T> a = accel(px, pv);
        for (std::size_t p = 0; p < planes.size() && p < kMaxPlanes; ++p) {
            const T an = glm::dot(planes[p].normal, a);
            if (contact[p] && an < T(0))
                a -= an * planes[p].normal;
        }
        return a;
    };
    const Vec3<T> start = x;
    int bounces = 0;
    T remaining = dt;
    for (int event = 0; event < kMaxEvents && remaining > T(0); ++event) {
        for (std::size_t p = 0; p < planes.size() && p < kMaxPlanes; ++p) {
            contact[p] = false; // decide each plane afresh with the unconstrained acceleration
            if (restsOn(planes[p], x, v) && glm::dot(planes[p].normal, accel(x, v)) < T(0)) {
                contact[p] = true;
                snapOnto(planes[p], x);
                v -= glm::dot(planes[p].normal, v) * planes[p].normal;
            }
        }
        std::optional<T> tau;
        std::size_t hit = 0;
        for (std::size_t p = 0; p < planes.size() && p < kMaxPlanes; ++p) {
            if (contact[p])
                continue;
            const auto t = timeOfImpactWithHole(integrator, planes[p], x, v, remaining, constrained);
            if (t && (!tau || *t < *tau)) {
                tau = t;
                hit = p;
            }
        }
        if (!tau) {
            integrate(integrator, x, v, remaining, constrained);
            remaining = T(0);
            break;
        }
        if (*tau > T(0))
            integrate(integrator, x, v, *tau, constrained);
        const PlaneT<T>& plane = planes[hit];
        snapOnto(plane, x);
        const T vn = glm::dot(plane.normal, v);
        const T an = glm::dot(plane.normal, accel(x, v));
        if (vn < T(0)) {
            v -= (T(1) + restitution) * vn * plane.normal;
            ++bounces;
            if (restitution < T(1) && an < T(0) && -restitution * vn < -an * dt)
                v -= glm::dot(plane.normal, v) * plane.normal; // too weak to leave: rest
        }
        remaining -= *tau;
    }
    bounces += keepInside(planes, restitution, start, x, v);
    return bounces;
}

namespace collision_detail {

/// The reflect and clamp rules' share for one plane: a body that ended the step beyond `plane`
/// (and not through its hole) is moved back along the normal by `back` times its depth (2:
/// mirrored across the plane, 1: put on it), and its normal velocity reflected with
/// restitution if it still moves outward. A body in the plane's shaft is kept within the
/// shaft's side wall (pushIntoShaft): the wall is a surface of the pass like the plane itself,
/// not left to the last line of defence, because particles that fall into the hole slide
/// around the wall at the grille for good (16,000 a step of a million-particle swarm, each
/// through the whole rule one by one: a third of its step). Written with selects instead of
/// branches, so the same function serves one body and a vectorised loop over a swarm's arrays;
/// a body that is inside is left exactly as it was. Returns whether it moved the body; counts
/// the bounce. `kMayHaveHole` false, for a plane known to have none, skips the shaft's
/// arithmetic (a swarm's pass picks it per plane; it changes no result). `plane` is a PlaneT or
/// an AxisPlaneT.
template <bool kMayHaveHole = true, class Geometry, class T>
inline bool pushBack(const Geometry& plane, T restitution, T back, const Vec3<T>& start, Vec3<T>& x, Vec3<T>& v,
                     int& bounces)
{
    const T d = plane.distance(x);
    const bool excused = kMayHaveHole && throughHole(plane, start, x);
    const bool beyond = (d < T(0)) & !excused;
    plane.moveAlong(x, -(beyond ? back * d : T(0)));
    const T vn = plane.along(v);
    const bool bounce = beyond & (vn < T(0));
    plane.moveAlong(v, -(bounce ? (T(1) + restitution) * vn : T(0)));
    bounces += int(bounce);
    if constexpr (kMayHaveHole)
        return pushIntoShaft(plane, restitution, (d < T(0)) & excused, x, v, bounces) | beyond;
    else
        return beyond;
}

} // namespace collision_detail

/// One plane's share of a pass of the reflect rule: mirror the body back across it.
template <bool kMayHaveHole = true, class Geometry, class T>
inline bool mirrorBack(const Geometry& plane, T restitution, const Vec3<T>& start, Vec3<T>& x, Vec3<T>& v,
                       int& bounces)
{
    return collision_detail::pushBack<kMayHaveHole>(plane, restitution, T(2), start, x, v, bounces);
}

/// The clamp rule's share for one plane: put the body back on it.
template <bool kMayHaveHole = true, class Geometry, class T>
inline bool snapBack(const Geometry& plane, T restitution, const Vec3<T>& start, Vec3<T>& x, Vec3<T>& v,
                     int& bounces)
{
    return collision_detail::pushBack<kMayHaveHole>(plane, restitution, T(1), start, x, v, bounces);
}

/// Two opposite walls of a box, neither with a hole: the slab lo <= x[axis] <= hi.
template <class T>
struct SlabT {
    int axis;
    T lo, hi;
};

namespace collision_detail {

/// The indices in `planes` of the walls facing +axis and -axis (the inner one of each; -1 when there
/// is none), leaving out walls with a hole unless `withHoles`.
template <class T>
inline std::array<int, 2> wallsOnAxis(std::span<const PlaneT<T>> planes, int axis, bool withHoles)
{
    std::array<int, 2> walls{-1, -1};
    for (std::size_t p = 0; p < planes.size(); ++p) {
        if (planes[p].axis() != axis || (!withHoles && planes[p].holeRadius > T(0)))
            continue;
        // Of two walls on one side the inner one (a larger offset on either side: the floor, not
        // the grille below its hole): a point clear of it is clear of the other.
        int& wall = walls[planes[p].normal[axis] > T(0) ? 0 : 1];
        if (wall < 0 || planes[p].offset > planes[std::size_t(wall)].offset)
            wall = static_cast<int>(p);
    }
    return walls;
}

} // namespace collision_detail

/// The slabs among `planes` (at most one an axis), so the reflect rule can fold a body into
/// each in one go. Returns how many there are.
template <class T>
inline int boxSlabs(std::span<const PlaneT<T>> planes, std::array<SlabT<T>, 3>& slabs)
{
    int count = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const auto [low, high] = collision_detail::wallsOnAxis(planes, axis, false);
        if (low >= 0 && high >= 0 && planes[std::size_t(low)].offset < -planes[std::size_t(high)].offset)
            slabs[std::size_t(count++)] =
                SlabT<T>{axis, planes[std::size_t(low)].offset, -planes[std::size_t(high)].offset};
    }
    return count;
}

/// The reflect rule between a slab's two walls in closed form, for a body still beyond one after
/// a pass (faster than the room is wide in a step). Mirroring it across that wall, then across
/// the other, and so on until it is inside, puts it where its coordinate folds into the slab:
/// the slab's mirror images repeat every 2 (hi - lo). Its velocity along the axis changes sign
/// and keeps e of its size at every wall it is moving towards when mirrored: the first one if it
/// moved outward, every later one if it still moves at all. Branch-free like pushBack, so a swarm runs
/// it as a vectorised loop; a body inside the slab is left exactly as it was. Beyond 2^22 slab
/// widths (or not finite) it is left to the last line of defence. Returns the bounces, in T
/// (an int here would stop GCC vectorising the swarm's loop, whose sum this is).
template <class T>
inline T foldIntoSlab(const SlabT<T>& slab, T restitution, T& c, T& cv)
{
    constexpr int kBits = 22;
    const T width = slab.hi - slab.lo;
    const T u = c - slab.lo;
    const T q = u / width;
    const bool below = u < T(0);
    const bool fold = (below | (q > T(1))) & (std::abs(q) < T(1 << kBits));
    const T walls = below ? std::ceil(-q) : std::ceil(q) - T(1);
    const T period = T(2) * width;
    const T r = u - period * std::floor(u / period);
    const T folded = std::clamp(r <= width ? r : period - r, T(0), width);
    c = fold ? slab.lo + folded : c;
    const T first = (below ? -cv : cv) > T(0) ? T(1) : T(0);
    const T later = cv != T(0) ? walls - T(1) : T(0);
    const T moving = fold ? first + later : T(0);
    const T hits = restitution > T(0) ? moving : std::min(moving, T(1)); // e = 0: the first stops it
    // e^hits by squaring, written out for each bit: a straight line a vectorised loop can hold.
    const int bits = static_cast<int>(hits);
    T factor = T(1), power = restitution;
    [&]<int... kBit>(std::integer_sequence<int, kBit...>) {
        ((factor *= (bits >> kBit & 1) ? power : T(1), power *= power), ...);
    }(std::make_integer_sequence<int, kBits + 1>{});
    cv *= (bits & 1) ? -factor : factor;
    return hits;
}

/// The classic response's rule, applied after a full step from `start`: mirror the body back
/// across every surface it passed, repeatedly, so even a body fast enough to cross the room ends
/// inside; one still outside after a pass is folded into the box's slabs first. Split from the
/// step so swarms can integrate a whole block first and then apply it; a swarm runs the first
/// pass (`passesDone` 1) and the fold (2) itself and calls this only for the bodies still outside.
template <class T>
inline int reflectAfterStep(std::span<const PlaneT<T>> planes, T restitution, const Vec3<T>& start, Vec3<T>& x,
                            Vec3<T>& v, int passesDone = 0)
{
    int bounces = 0;
    for (int pass = passesDone; pass < collision_detail::kMaxEvents; ++pass) {
        if (pass == 1) {
            std::array<SlabT<T>, 3> slabs;
            const int count = boxSlabs(planes, slabs);
            for (int s = 0; s < count; ++s) {
                const SlabT<T>& slab = slabs[std::size_t(s)];
                bounces += static_cast<int>(foldIntoSlab(slab, restitution, x[slab.axis], v[slab.axis]));
            }
        }
        bool mirrored = false;
        for (const PlaneT<T>& plane : planes)
            mirrored |= mirrorBack(plane, restitution, start, x, v, bounces);
        if (!mirrored)
            break;
    }
    return bounces + collision_detail::keepInside(planes, restitution, start, x, v);
}

/// The clamp response's rule after a full step from `start`: put the body back on every
/// surface it passed (`passesDone` 1: a swarm has done that pass, only the last line of
/// defence remains).
template <class T>
inline int clampAfterStep(std::span<const PlaneT<T>> planes, T restitution, const Vec3<T>& start, Vec3<T>& x,
                          Vec3<T>& v, int passesDone = 0)
{
    int bounces = 0;
    if (passesDone == 0)
        for (const PlaneT<T>& plane : planes)
            snapBack(plane, restitution, start, x, v, bounces);
    return bounces + collision_detail::keepInside(planes, restitution, start, x, v);
}

/// The classic response: a full step, then reflectAfterStep.
template <class T, class Accel>
inline int stepReflect(Integrator integrator, std::span<const PlaneT<T>> planes, T restitution, Vec3<T>& x,
                       Vec3<T>& v, T dt, Accel&& accel)
{
    const Vec3<T> start = x;
    integrate(integrator, x, v, dt, accel);
    return reflectAfterStep(planes, restitution, start, x, v);
}

/// A full step, then clampAfterStep.
template <class T, class Accel>
inline int stepClamp(Integrator integrator, std::span<const PlaneT<T>> planes, T restitution, Vec3<T>& x,
                     Vec3<T>& v, T dt, Accel&& accel)
{
    const Vec3<T> start = x;
    integrate(integrator, x, v, dt, accel);
    return clampAfterStep(planes, restitution, start, x, v);
}

namespace collision_detail {

/// lowerClearance's loop for one form of the plane's geometry, taken by value so the stores
/// to margin cannot change it. For a wall (AxisPlaneT) the distance is one coordinate, and the
/// loop reads one array instead of three.
template <class Geometry, class T>
inline std::uint32_t lowerClearanceOf(const Geometry plane, T tolerance, const T* __restrict x,
                                      const T* __restrict y, const T* __restrict z, std::size_t n,
                                      T* __restrict margin)
{
    std::uint32_t beyond = 0; // 32 bits: a counter as wide as T keeps the loop in one vector width
    for (std::size_t k = 0; k < n; ++k) {
        const T d = plane.distance(Vec3<T>(x[k], y[k], z[k]));
        const T clearance = d - tolerance;
        margin[k] = clearance < margin[k] ? clearance : margin[k]; // not std::min: its reference stops the vectoriser
        beyond += static_cast<std::uint32_t>(d < T(0));
    }
    return beyond;
}

} // namespace collision_detail

/// Lowers margin[k] to the clearance of point k (SoA arrays, n of them) from `plane`: its
/// distance beyond the plane's contact tolerance, so a point is clear of every plane when its
/// smallest margin is positive. A step whose start and end are clear of every plane needs no
/// collision rule at all; the others get the full rule. Plane-major and in the scalar type
/// (three multiply-adds and a min a point, no conversion to flags per plane), so each loop is
/// a straight line of arithmetic that vectorises. (A path that leaves and re-enters within one
/// step, an apex beyond the ceiling, is not seen by this end-point test.) Returns how many of
/// the points are beyond the plane itself, which tells whether the plane's rule has work.
template <class T>
inline std::size_t lowerClearance(const PlaneT<T>& plane, const T* __restrict x, const T* __restrict y,
                                  const T* __restrict z, std::size_t n, T* __restrict margin)
{
    const T tolerance = collision_detail::contactTolerance(plane);
    return withPlaneGeometry(plane, [&](const auto geometry) {
        return collision_detail::lowerClearanceOf(geometry, tolerance, x, y, z, n, margin);
    });
}

/// The six walls of a box among a world's planes (a hole in one is allowed: the surface test
/// that uses this is only a filter), for testing many points against all six in one loop.
template <class T>
struct BoxWallsT {
    std::array<T, 3> lo, hi;           ///< a point is beyond none of the walls when lo <= x <= hi
    std::array<T, 3> clearLo, clearHi; ///< and clear of them (beyond the contact tolerance) between these
    std::array<int, 6> plane;          ///< the walls' indices in the span: low x, high x, low y, ...
    std::uint64_t mask = 0;            ///< bits of those indices (below 64)
};

/// The box whose walls are among `planes`, if every axis has a wall on each side.
template <class T>
inline std::optional<BoxWallsT<T>> boxWalls(std::span<const PlaneT<T>> planes)
{
    BoxWallsT<T> box;
    for (int axis = 0; axis < 3; ++axis) {
        const auto [low, high] = collision_detail::wallsOnAxis(planes, axis, true);
        if (low < 0 || high < 0 || low >= 64 || high >= 64)
            return std::nullopt;
        const PlaneT<T>& l = planes[std::size_t(low)];
        const PlaneT<T>& h = planes[std::size_t(high)];
        const auto i = std::size_t(axis);
        box.lo[i] = l.offset;
        box.hi[i] = -h.offset;
        box.clearLo[i] = l.offset + collision_detail::contactTolerance(l);
        box.clearHi[i] = -h.offset - collision_detail::contactTolerance(h);
        box.plane[2 * i] = low;
        box.plane[2 * i + 1] = high;
        box.mask |= std::uint64_t(1) << low | std::uint64_t(1) << high;
    }
    return box;
}

/// The region clear of the box's walls (beyond their contact tolerance), by value, so the loops
/// that hold one need no alias checks. `margin` is lowerClearance's margin for all six walls
/// (positive: clear).
template <class T>
struct ClearRegionT {
    T xl, xh, yl, yh, zl, zh;

    explicit ClearRegionT(const BoxWallsT<T>& box)
        : xl(box.clearLo[0]), xh(box.clearHi[0]), yl(box.clearLo[1]), yh(box.clearHi[1]), zl(box.clearLo[2]),
          zh(box.clearHi[2])
    {
    }
    T margin(T a, T b, T c) const
    {
        using collision_detail::lesser;
        return lesser(lesser(lesser(a - xl, xh - a), lesser(b - yl, yh - b)), lesser(c - zl, zh - c));
    }
};

/// lowerClearance for all six walls of a box in one loop: each coordinate is read once and the
/// margins written once, where six plane-by-plane loops read and wrote the margins six times
/// (this was a sixth of a swarm step). A point beyond a wall is never clear of it (x < lo
/// implies x < clearLo). Sets margin[k]; the other planes then lower it.
template <class T>
inline void setClearanceInBox(const BoxWallsT<T>& box, const T* __restrict x, const T* __restrict y,
                              const T* __restrict z, std::size_t n, T* __restrict margin)
{
    const ClearRegionT<T> region(box);
    for (std::size_t k = 0; k < n; ++k)
        margin[k] = region.margin(x[k], y[k], z[k]);
}

/// unclear[k] = 1 for the points not clear of the box's walls, 0 for the others; returns how many
/// there are. (Counting first and marking only when some are was measured slower: one pass
/// fewer where particles meet the walls outweighs the flags written for nothing in flight.)
/// The test is the margin's sign, not six comparisons joined by `and` (the same answer: with
/// gradual underflow x - lo > 0 exactly when x > lo, and a NaN the rule leaves as it is): the
/// comparisons become a chain of six masked compares, each waiting for the last, and measured
/// 2.2 times slower than five minima and one compare on a block in L1 (0.25 against 0.12 ns a
/// particle), a fifth of a swarm's step in flight.
template <class T>
inline std::uint32_t markUnclearInBox(const ClearRegionT<T> region, const T* __restrict x, const T* __restrict y,
                                      const T* __restrict z, std::size_t n, std::uint8_t* __restrict unclear)
{
    std::uint32_t count = 0; // 32 bits, as in lowerClearance
    for (std::size_t k = 0; k < n; ++k) {
        unclear[k] = static_cast<std::uint8_t>(!(region.margin(x[k], y[k], z[k]) > T(0)));
        count += unclear[k];
    }
    return count;
}

/// The smallest and the largest of each coordinate over some points. A point is beyond a plane
/// whose normal is a coordinate axis exactly when the bound on the plane's side is, so one loop
/// of six minima and maxima tells which of a room's walls, and which other axis-aligned planes
/// (the grille below a hole), some of a block's points crossed: counting them wall by wall took
/// six comparisons and six sums a point, and a second loop for each other plane.
template <class T>
struct BoundsT {
    std::array<T, 3> lo, hi;

    /// Whether some of the points are beyond `plane`, whose axis() must be 0, 1 or 2: what
    /// lowerClearance's count > 0 says of them (its d = sign c - offset < 0 exactly when
    /// sign c < offset).
    bool beyond(const PlaneT<T>& plane) const
    {
        const int axis = plane.axis();
        const auto i = static_cast<std::size_t>(axis);
        return plane.normal[axis] > T(0) ? lo[i] < plane.offset : -hi[i] < plane.offset;
    }
};

/// The bounds of n points (SoA arrays); a NaN coordinate is passed over, as lowerClearance
/// counts it beyond no plane. The minima and maxima are kept lane by lane in whole vectors of
/// kLanes floats and reduced at the end: GCC does not vectorise a floating-point minimum taken
/// over a loop (it would reorder it), but it vectorises one taken element by element.
template <class T>
inline BoundsT<T> boundsOf(const T* __restrict x, const T* __restrict y, const T* __restrict z, std::size_t n)
{
    using collision_detail::lesser;
    const auto greater = [](T a, T b) { return a < b ? b : a; };
    constexpr std::size_t kLanes = 64 / sizeof(T);
    constexpr T kInf = std::numeric_limits<T>::infinity();
    T x0[kLanes], x1[kLanes], y0[kLanes], y1[kLanes], z0[kLanes], z1[kLanes];
    std::fill_n(x0, kLanes, kInf), std::fill_n(y0, kLanes, kInf), std::fill_n(z0, kLanes, kInf);
    std::fill_n(x1, kLanes, -kInf), std::fill_n(y1, kLanes, -kInf), std::fill_n(z1, kLanes, -kInf);
    std::size_t k = 0;
    for (; k + kLanes <= n; k += kLanes) {
        for (std::size_t j = 0; j < kLanes; ++j) {
            x0[j] = lesser(x0[j], x[k + j]), x1[j] = greater(x1[j], x[k + j]);
            y0[j] = lesser(y0[j], y[k + j]), y1[j] = greater(y1[j], y[k + j]);
            z0[j] = lesser(z0[j], z[k + j]), z1[j] = greater(z1[j], z[k + j]);
        }
    }
    for (std::size_t j = 0; k < n; ++k, ++j) // the last, partial vector
        x0[j] = lesser(x0[j], x[k]), x1[j] = greater(x1[j], x[k]), y0[j] = lesser(y0[j], y[k]),
        y1[j] = greater(y1[j], y[k]), z0[j] = lesser(z0[j], z[k]), z1[j] = greater(z1[j], z[k]);
    BoundsT<T> bounds{{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}};
    for (std::size_t j = 0; j < kLanes; ++j) {
        bounds.lo = {lesser(bounds.lo[0], x0[j]), lesser(bounds.lo[1], y0[j]), lesser(bounds.lo[2], z0[j])};
        bounds.hi = {greater(bounds.hi[0], x1[j]), greater(bounds.hi[1], y1[j]), greater(bounds.hi[2], z1[j])};
    }
    return bounds;
}

/// lowerDepth for the six walls of a box in one loop, each coordinate read once (as
/// setClearanceInBox for lowerClearance). A wall with a hole must be left to lowerDepth, which
/// knows the hole's shaft: give it an infinite bound here.
template <class T>
inline void lowerDepthInBox(const std::array<T, 3>& lo, const std::array<T, 3>& hi, const T* __restrict x,
                            const T* __restrict y, const T* __restrict z, std::size_t n, T* __restrict depth)
{
    const T x0 = lo[0], x1 = hi[0], y0 = lo[1], y1 = hi[1], z0 = lo[2], z1 = hi[2];
    for (std::size_t k = 0; k < n; ++k) {
        const T a = x[k], b = y[k], c = z[k];
        using collision_detail::lesser;
        const T d = lesser(lesser(lesser(a - x0, x1 - a), lesser(b - y0, y1 - b)), lesser(c - z0, z1 - c));
        depth[k] = d < depth[k] ? d : depth[k];
    }
}

namespace collision_detail {

/// lowerDepth's loop for one form of the geometry of a plane with a hole (by value, as
/// lowerClearanceOf's): points within innerSquared of the hole's axis are not counted.
template <class Geometry, class T>
inline void lowerDepthOf(const Geometry plane, T innerSquared, const T* __restrict x, const T* __restrict y,
                         const T* __restrict z, std::size_t n, T* __restrict depth)
{
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3<T> p(x[k], y[k], z[k]);
        const auto rho = plane.fromHoleAxis(p);
        const T counted = glm::dot(rho, rho) < innerSquared ? std::numeric_limits<T>::infinity() : plane.distance(p);
        depth[k] = counted < depth[k] ? counted : depth[k];
    }
}

/// lowerDepth's loop for a plane without a hole: the distance alone, which for a wall
/// (AxisPlaneT) reads one array instead of three.
template <class Geometry, class T>
inline void lowerDepthWithoutHole(const Geometry plane, const T* __restrict x, const T* __restrict y,
                                  const T* __restrict z, std::size_t n, T* __restrict depth)
{
    for (std::size_t k = 0; k < n; ++k) {
        const T d = plane.distance(Vec3<T>(x[k], y[k], z[k]));
        depth[k] = d < depth[k] ? d : depth[k];
    }
}

} // namespace collision_detail

/// Lowers depth[k] to point k's signed distance from the plane (no tolerance): a point whose
/// smallest depth is negative is outside some plane and needs the rest of a collision rule. A
/// point in the shaft below the plane's hole, within its radius, is where it may be
/// (keepInShaft would leave it): it does not lower its depth for this plane. "Within" leaves 8
/// units in the last place for rounding; pushIntoShaft puts a body 16 inside the wall.
template <class T>
inline void lowerDepth(const PlaneT<T>& plane, const T* __restrict x, const T* __restrict y, const T* __restrict z,
                       std::size_t n, T* __restrict depth)
{
    const T inner = plane.holeRadius * (T(1) - T(8) * std::numeric_limits<T>::epsilon());
    const bool hole = plane.holeRadius > T(0);
    withPlaneGeometry(plane, [&](const auto geometry) {
        if (hole)
            collision_detail::lowerDepthOf(geometry, inner * inner, x, y, z, n, depth);
        else
            collision_detail::lowerDepthWithoutHole(geometry, x, y, z, n, depth);
    });
}

/// Whether x is clear of every plane (see lowerClearance).
template <class T>
inline bool clearOfAll(std::span<const PlaneT<T>> planes, const Vec3<T>& x)
{
    T margin = std::numeric_limits<T>::infinity();
    for (const PlaneT<T>& plane : planes)
        lowerClearance(plane, &x.x, &x.y, &x.z, 1, &margin);
    return margin > T(0);
}

/// One step of a body with the chosen response; returns the number of bounces.
template <class T, class Accel>
inline int stepWithCollisions(CollisionResponse response, Integrator integrator, std::span<const PlaneT<T>> planes,
                              T restitution, Vec3<T>& x, Vec3<T>& v, T dt, Accel&& accel)
{
    if (planes.empty()) {
        integrate(integrator, x, v, dt, accel);
        return 0;
    }
    switch (response) {
    case CollisionResponse::Exact: return stepExact(integrator, planes, restitution, x, v, dt, accel);
    case CollisionResponse::Reflect: return stepReflect(integrator, planes, restitution, x, v, dt, accel);
    case CollisionResponse::Clamp: return stepClamp(integrator, planes, restitution, x, v, dt, accel);
    }
    return 0;
}

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
