#pragma once
// The three collision responses of pba/collision.hpp as rules for one body: the exact response
// (time of impact, bounce, rest of the step), reflect and clamp (after a full step), and the
// last line of defence that keeps every body inside. Each is a template over the scalar type
// and the acceleration, and written over the primitives PlaneT and AxisPlaneT share, so the
// same rule serves a double-precision Particle and a float swarm's vectorised passes.
// Private to the core.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <utility>

#include "pba/collision.hpp"
#include "pba/integrator.hpp"
#include "surfaces/time_of_impact.hpp"

namespace pba {

namespace collision_detail {

/// How many impacts one step may resolve before the rest of it is clamped (a body
/// wedged in a corner with e close to 1 would otherwise loop).
inline constexpr int kMaxEvents = 16;

/// std::min by value, for the loops over a swarm's arrays: std::min takes and returns
/// references, and GCC 12 stopped vectorising a swarm's box test ("complicated access pattern")
/// when a change elsewhere in the step altered how it was inlined. The same result as std::min.
template <class T>
inline T lesser(T a, T b)
{
    return b < a ? b : a;
}

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

/// Puts a body in the shaft below a hole (`inShaft`) that is at or beyond the shaft's side wall
/// back just inside it, and reflects its outward radial velocity with restitution. A body that
/// is not at the wall is left exactly as it was. Returns whether it moved the body; counts the
/// bounce. Only scalar code runs it (a Particle's rule, and the whole rule a swarm hands the few
/// bodies at the wall to), so it branches: the rule asks it about every plane, holes or not,
/// and when it computed the shaft's square root and division for all of them and then selected,
/// that was a quarter of the time a fast body's whole rule took.
/// `plane` is a PlaneT or an AxisPlaneT, as for every function of the rule below.
template <class Geometry, class T>
inline bool pushIntoShaft(const Geometry& plane, T restitution, bool inShaft, Vec3<T>& x, Vec3<T>& v, int& bounces)
{
    if (!inShaft)
        return false;
    const auto rho = plane.fromHoleAxis(x);
    const T r = glm::length(rho);
    if (r < plane.holeRadius || !(r > T(0)))
        return false;
    const auto out = rho / r;
    plane.moveInPlane(x, -(r - plane.holeRadius * (T(1) - T(16) * std::numeric_limits<T>::epsilon())) * out);
    const T vr = plane.alongInPlane(v, out);
    if (vr > T(0)) {
        plane.moveInPlane(v, -((T(1) + restitution) * vr) * out);
        ++bounces;
    }
    return true;
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

/// Whether x is on the inner side of every plane, where the rules after a step change nothing:
/// the common case, tested first so that a body far from the walls (most of a cloth's particles,
/// every step) costs a dot product a plane rather than the rules' selects.
template <class T>
inline bool insideAll(std::span<const PlaneT<T>> planes, const Vec3<T>& x)
{
    bool inside = true;
    for (const PlaneT<T>& plane : planes)
        inside &= plane.distance(x) >= T(0);
    return inside;
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

/// The reflect and clamp rules' share for one plane: a body that ended the step beyond `plane`
/// (and not through its hole) is moved back along the normal by `back` times its depth (2:
/// mirrored across the plane, 1: put on it), and its normal velocity reflected with
/// restitution if it still moves outward. A body in the plane's shaft is kept within the
/// shaft's side wall (pushIntoShaft): the wall is a surface of the pass like the plane itself,
/// not left to the last line of defence, because bodies that fall into the hole can slide
/// around the wall at the grille step after step. Written with selects instead of branches,
/// so the same function serves one body and a vectorised loop over a swarm's arrays (the pass
/// over the floor, without the wall: `kShaftWall`); a body that is inside is left exactly as
/// it was. Returns whether it moved the body; counts the bounce. `kMayHaveHole` false, for a
/// plane known to have none, skips the shaft's arithmetic (a swarm's pass picks it per plane;
/// it changes no result). `plane` is a PlaneT or an AxisPlaneT.
/// `kShaftWall` false leaves the shaft's wall out (its square root and divisions): for a caller
/// that sees to the bodies in the shaft itself (a swarm's fused pass hands them to the whole rule).
template <bool kMayHaveHole = true, bool kShaftWall = true, class Geometry, class T>
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
    if constexpr (kMayHaveHole && kShaftWall)
        return pushIntoShaft(plane, restitution, (d < T(0)) & excused, x, v, bounces) | beyond;
    else
        return beyond;
}

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

/// The surfaces among the first 32 of `planes` that x is nearer than `reach` to (or beyond), a bit
/// a plane: the contact passes' sweeps move a ball less than that, so the others are out of its
/// reach for the step (a sheet on the floor tests the floor, not the walls). `visits` reads it.
inline constexpr std::size_t kWallBits = 32;
template <class T>
inline std::uint32_t wallsWithin(std::span<const PlaneT<T>> planes, const Vec3<T>& x, T reach)
{
    std::uint32_t walls = 0;
    for (std::size_t p = 0; p < std::min(planes.size(), kWallBits); ++p)
        if (planes[p].distance(x) < reach)
            walls |= 1u << p;
    return walls;
}

/// Whether plane p is to be visited for a ball whose walls within reach are `walls`: planes
/// beyond the 32nd always are.
inline bool visits(std::uint32_t walls, std::size_t p) { return p >= kWallBits || ((walls >> p) & 1u); }

/// Coulomb friction of a push off a surface: a body whose velocity changed by `normalChange` (m/s,
/// not negative) along the unit normal n loses up to mu times that of its velocity along the
/// surface, and never more than it has (friction stops a body; it never turns it back).
template <class T>
inline void rubAlong(const Vec3<T>& n, T mu, T normalChange, Vec3<T>& v)
{
    const Vec3<T> vt = v - glm::dot(n, v) * n;
    const T speed = glm::length(vt);
    if (speed > T(0))
        v -= std::min(T(1), mu * normalChange / speed) * vt;
}

/// v rubbed along a push that changed it by `change` (rubAlong along the push's direction, with its
/// size), written as selects so that the swarm's vectorised collision pass takes the same function
/// as a Particle's rule (afterStepWithFriction) and the swarm's whole rule.
template <class T>
inline Vec3<T> rubbedByPush(Vec3<T> v, const Vec3<T>& change, T mu)
{
    const T size = glm::length(change);
    const Vec3<T> n = change / size; // not finite where size is 0: not selected below
    const Vec3<T> vt = v - glm::dot(n, v) * n;
    const T speed = glm::length(vt);
    const T share = std::min(T(1), mu * size / speed);
    const bool rub = (size > T(0)) & (speed > T(0));
    for (int c = 0; c < 3; ++c)
        v[c] = rub ? v[c] - share * vt[c] : v[c];
    return v;
}

/// The acceleration a surface's friction adds to `a` (already rid of its part into the surface,
/// of size `pressing` = -a.n) for a body resting on it at velocity v: what would stop it within
/// dt if that takes no more than mu times the pressing, else that much against it. So a body
/// at rest stays while the pull along the surface is within the friction cone (static), and a
/// sliding one is slowed by mu |a.n| (kinetic): Coulomb's law with one mu for both.
template <class T>
inline Vec3<T> restingFriction(const Vec3<T>& n, T mu, T pressing, const Vec3<T>& v, const Vec3<T>& a, T dt)
{
    const Vec3<T> stop = -((v - glm::dot(n, v) * n) / dt + (a - glm::dot(n, a) * n));
    const T needed = glm::length(stop);
    const T limit = mu * pressing;
    return needed <= limit ? stop : (limit / needed) * stop;
}

/// The planes a ball of `radius` meets with its centre (PlaneT::inflatedBy), in `room` (up to
/// kMaxBallPlanes planes; those beyond are left out); radius 0 hands back `planes` themselves, so a
/// point is stepped exactly as it was before balls had radii.
inline constexpr std::size_t kMaxBallPlanes = 8;
template <class T>
inline std::span<const PlaneT<T>> ballPlanes(std::span<const PlaneT<T>> planes, T radius,
                                             std::array<PlaneT<T>, kMaxBallPlanes>& room)
{
    if (radius == T(0))
        return planes;
    const std::size_t n = std::min(planes.size(), kMaxBallPlanes);
    for (std::size_t p = 0; p < n; ++p)
        room[p] = planes[p].inflatedBy(radius);
    return {room.data(), n};
}

/// What a step's caller may learn of each stretch of free flight along the body's actual path:
/// wrap(accel) is the acceleration the integrator then takes (so the caller sees its stages), and
/// close(dt, v0, v1) ends the stretch. The World's book of the energy sources' work is one; by
/// default nothing is kept, at no cost.
struct NoFlightBook {
    template <class Accel>
    Accel& wrap(Accel& accel) const { return accel; }
    template <class T>
    void close(T, const Vec3<T>&, const Vec3<T>&) const {}
};

/// One stretch of free flight of the actual path, told to the book.
template <class T, class Accel, class Book>
inline void flyBooked(Integrator integrator, Vec3<T>& x, Vec3<T>& v, T dt, Accel& accel, Book& book)
{
    const Vec3<T> v0 = v;
    integrate(integrator, x, v, dt, book.wrap(accel));
    book.close(dt, v0, v);
}

/// The exact response. Returns the number of bounces during the step.
///
/// Resting contact: a body on a surface whose net acceleration pushes into it is held
/// there by removing the normal components of its velocity and acceleration (the
/// surface's normal force), so it neither sinks nor bounces an endless number of
/// zero-length times. With e < 1 a rebound too weak to leave the surface for one full
/// step (slower than |a.n| dt) becomes such a contact; with e = 1 no energy may be
/// lost, so every rebound is kept.
template <class T, class Accel, class Book = NoFlightBook>
inline int stepExact(Integrator integrator, std::span<const PlaneT<T>> planes, T restitution, Vec3<T>& x,
                     Vec3<T>& v, T dt, Accel&& accel, T friction = T(0), Book&& book = Book{})
{
    using namespace collision_detail;
    constexpr std::size_t kMaxPlanes = 8;
    std::array<bool, kMaxPlanes> contact{};
    auto constrained = [&](const Vec3<T>& px, const Vec3<T>& pv) {
        Vec3<T> a = accel(px, pv);
        for (std::size_t p = 0; p < planes.size() && p < kMaxPlanes; ++p) {
            const T an = glm::dot(planes[p].normal, a);
            if (contact[p] && an < T(0)) {
                a -= an * planes[p].normal;
                if (friction > T(0))
                    a += restingFriction(planes[p].normal, friction, -an, pv, a, dt);
            }
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
            flyBooked(integrator, x, v, remaining, constrained, book);
            remaining = T(0);
            break;
        }
        if (*tau > T(0))
            flyBooked(integrator, x, v, *tau, constrained, book);
        const PlaneT<T>& plane = planes[hit];
        snapOnto(plane, x);
        const T vn = glm::dot(plane.normal, v);
        const T an = glm::dot(plane.normal, accel(x, v));
        if (vn < T(0)) {
            v -= (T(1) + restitution) * vn * plane.normal;
            if (friction > T(0))
                rubAlong(plane.normal, friction, -(T(1) + restitution) * vn, v);
            ++bounces;
            if (restitution < T(1) && an < T(0) && -restitution * vn < -an * dt)
                v -= glm::dot(plane.normal, v) * plane.normal; // too weak to leave: rest
        }
        remaining -= *tau;
    }
    bounces += keepInside(planes, restitution, start, x, v);
    return bounces;
}

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
/// moved outward, every later one if it still moves at all. A body inside the slab is left
/// exactly as it was. Beyond 2^22 slab widths (or not finite) it is left to the last line of
/// defence. Returns the bounces.
/// Only the scalar whole rule reaches it (a Particle's, and a swarm's for the few bodies its
/// vectorised pass over the floor leaves), so it may branch: e^hits by squaring visits only the
/// bits that hits has. It once ran in a swarm's vectorised loop, written out for all 23 bits;
/// the whole rule spent 38% of its time there for bodies that cross the room a few times a step.
/// The products are the same, so the result is the same to the bit.
template <class T>
inline int foldIntoSlab(const SlabT<T>& slab, T restitution, T& c, T& cv)
{
    constexpr int kBits = 22;
    const T width = slab.hi - slab.lo;
    const T u = c - slab.lo;
    const T q = u / width;
    const bool below = u < T(0);
    if (!((below || q > T(1)) && std::abs(q) < T(1 << kBits)))
        return 0;
    const T walls = below ? std::ceil(-q) : std::ceil(q) - T(1);
    const T period = T(2) * width;
    const T r = u - period * std::floor(u / period);
    c = slab.lo + std::clamp(r <= width ? r : period - r, T(0), width);
    const int first = (below ? -cv : cv) > T(0) ? 1 : 0;
    const int later = cv != T(0) ? static_cast<int>(walls) - 1 : 0;
    const int hits = restitution > T(0) ? first + later : std::min(first + later, 1); // e = 0: the first stops it
    T factor = T(1), power = restitution;
    for (int bits = hits; bits != 0; bits >>= 1, power *= power)
        if (bits & 1)
            factor *= power;
    cv *= (hits & 1) ? -factor : factor;
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
    if (passesDone == 0 && collision_detail::insideAll(planes, x))
        return 0;
    int bounces = 0;
    for (int pass = passesDone; pass < collision_detail::kMaxEvents; ++pass) {
        if (pass == 1) {
            std::array<SlabT<T>, 3> slabs;
            const int count = boxSlabs(planes, slabs);
            for (int s = 0; s < count; ++s) {
                const SlabT<T>& slab = slabs[std::size_t(s)];
                bounces += foldIntoSlab(slab, restitution, x[slab.axis], v[slab.axis]);
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
    if (passesDone == 0 && collision_detail::insideAll(planes, x))
        return 0;
    int bounces = 0;
    if (passesDone == 0)
        for (const PlaneT<T>& plane : planes)
            snapBack(plane, restitution, start, x, v, bounces);
    return bounces + collision_detail::keepInside(planes, restitution, start, x, v);
}

/// The reflect or clamp rule after a full step from `start`, with Coulomb friction from the push
/// it gave: the body's velocity changed by dv along the push, and loses up to mu |dv| along the
/// surface (rubbedByPush). A push on a body that arrived no faster than twice `restingSpeed` (what
/// its acceleration gives in one step, |a| dt) is resting contact, not a bounce, as the exact
/// rule's rebound too weak to leave the surface for a step: a body lying on the floor is pulled
/// below it by every step and pushed back, and a rope's end counted a bounce nearly every step.
/// With `restingDrift` (the coupled rule's: a rope's or a cloth's particles) that push, up to the
/// mirror's own hop, is resting contact in the motion too: the body is put back on the surface and
/// stays there (the clamp rule without a rebound), where the mirror and its rebound kept a rope's
/// end, pulled down by its springs at three times gravity, hopping every third step for as long
/// as it lay there. And the friction's change of velocity moves the position by restingDrift
/// times it (the share of the step's drift that the end velocity drives, times dt): friction that
/// stops the velocity stops the step's slide too, where a rope's end lying on the floor crept
/// 2.5 mm/s with zero velocity.
template <class T>
inline int afterStepWithFriction(CollisionResponse response, std::span<const PlaneT<T>> planes, T restitution,
                                 T friction, T restingSpeed, const Vec3<T>& start, Vec3<T>& x, Vec3<T>& v,
                                 std::optional<T> restingDrift = std::nullopt)
{
    const Vec3<T> before = v, end = x;
    int bounces = response == CollisionResponse::Clamp ? clampAfterStep(planes, restitution, start, x, v)
                                                       : reflectAfterStep(planes, restitution, start, x, v);
    Vec3<T> change = v - before;
    T size = glm::length(change);
    if (!(size > T(0)))
        return bounces;
    // The coupled rule's mirror lifts a body pulled onto the surface by its depth, which keeps
    // it hopping at 2 |a| dt / (1 - e^2) (the lift giving back what e takes): an arrival no
    // faster is the rule's own hop, not an impact (a velocity-Verlet rope's end hopped so).
    const T bounded = std::min(restitution, T(0.9));
    const T reach = restingDrift ? T(2) * restingSpeed / (T(1) - bounded * bounded) : T(2) * restingSpeed;
    const bool resting = !(-glm::dot(change / size, before) > reach);
    if (resting && restingDrift) {
        x = end;
        v = before;
        clampAfterStep(planes, T(0), start, x, v);
        change = v - before;
        size = glm::length(change);
    }
    if (friction > T(0) && size > T(0)) {
        const Vec3<T> pushed = v;
        v = rubbedByPush(v, change, friction);
        if (resting && restingDrift)
            x += (v - pushed) * *restingDrift;
    }
    return resting ? 0 : bounces;
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

/// One step of a body with the chosen response; returns the number of bounces.
/// `friction` is the Coulomb mu against the planes (0: none, and the step is exactly the
/// frictionless one). The exact response rubs while the body rests on a plane and at each bounce;
/// reflect and clamp rub with their push's impulse (afterStepWithFriction). `book` is told each
/// stretch of free flight the step takes (NoFlightBook).
template <class T, class Accel, class Book = NoFlightBook>
inline int stepWithCollisions(CollisionResponse response, Integrator integrator, std::span<const PlaneT<T>> planes,
                              T restitution, Vec3<T>& x, Vec3<T>& v, T dt, Accel&& accel, T friction = T(0),
                              Book&& book = Book{})
{
    if (planes.empty()) {
        flyBooked(integrator, x, v, dt, accel, book);
        return 0;
    }
    if (response == CollisionResponse::Exact)
        return stepExact(integrator, planes, restitution, x, v, dt, accel, friction, book);
    const Vec3<T> start = x, startVel = v;
    flyBooked(integrator, x, v, dt, accel, book);
    // The acceleration at the start again only when the rule pushed: most steps it does not.
    const bool pushed = !collision_detail::insideAll(planes, x);
    const T restingSpeed = pushed ? glm::length(accel(start, startVel)) * dt : T(0);
    return afterStepWithFriction(response, planes, restitution, friction, restingSpeed, start, x, v);
}

} // namespace pba
