#include "rigid_contact.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace pba {

namespace {

/// One direction an impulse acts in at a contact point: what an impulse of 1 along it does to
/// the body (v by u / m, L by r x u, omega by I^-1 (r x u)) and the mass the point feels along it,
/// worked out once so that each sweep is dot products and additions.
struct Row {
    dvec3 u{0.0};        ///< the direction, unit
    dvec3 angular{0.0};  ///< r x u
    dvec3 response{0.0}; ///< I^-1 (r x u), world frame
    double mass = 0.0;   ///< 1 / (1/m + (r x u) . I^-1 (r x u))
    double impulse = 0.0; ///< accumulated

    void setUp(const dvec3& direction, const dvec3& arm, double inverseMass, const dmat3& inverseInertia)
    {
        u = direction;
        angular = glm::cross(arm, direction);
        response = inverseInertia * angular;
        mass = 1.0 / (inverseMass + glm::dot(angular, response));
    }
    double speed(const dvec3& v, const dvec3& omega) const { return glm::dot(u, v) + glm::dot(angular, omega); }
};

struct Contact {
    dvec3 normal;    ///< into the room
    dvec3 arm;       ///< from the centre of mass to the point, world frame
    double gap;      ///< the point's distance from the surface (negative: beyond it)
    int surface;     ///< the plane's index; planes.size() + p for plane p's shaft wall
    int point = 0;   ///< the contact point's index
    double target = 0.0; ///< the normal speed the point should leave with
    bool bounces = false; ///< arriving faster than resting: it leaves at e times its speed
    Row along{}, across[2]{};

    /// For emplace_back, which builds a candidate in the vector: pushing a built one copied its
    /// 336 bytes, which was a tenth of a resting die's step.
    Contact(const dvec3& n, const dvec3& r, double depth, int plane, int index)
        : normal(n), arm(r), gap(depth), surface(plane), point(index)
    {
    }
};

/// Two unit vectors that complete n to an orthonormal frame.
void tangentsOf(const dvec3& n, dvec3 (&t)[2])
{
    const dvec3 other = std::abs(n.x) < 0.57735 ? dvec3(1.0, 0.0, 0.0) : dvec3(0.0, 1.0, 0.0);
    t[0] = glm::normalize(glm::cross(n, other));
    t[1] = glm::cross(n, t[0]);
}

/// Every point of the body at pose (x, r) that could meet a surface, with its gap: each contact
/// point against each plane (a sphere's point nearest the plane). A point over a floor hole
/// meets no floor; a body whose centre is below the floor and over the hole is in the hole's
/// shaft, and its points meet the shaft's wall instead.
/// Only the planes within `planeReach` of the centre are looked at (a die on the floor is near
/// one of a room's seven), and of their points those whose gap is below `pointReach`.
void candidates(const ContactBody& body, std::span<const Plane> planes, const dvec3& x, const dmat3& r,
                double planeReach, double pointReach, std::vector<Contact>& out)
{
    thread_local std::vector<dvec3> arms; // kept from call to call: no allocation a body and step
    arms.clear();
    const bool sphere = body.shape.type == ShapeType::Sphere;
    bool turned = false;
    for (std::size_t p = 0; p < planes.size(); ++p) {
        const Plane& plane = planes[p];
        const int shaft = int(planes.size() + p);
        const double centre = plane.distance(x);
        const bool inShaft = plane.holeRadius > 0.0 && centre < 0.0 && plane.overHole(x);
        if (!inShaft && centre > planeReach)
            continue;
        if (!sphere && !turned) {
            for (const dvec3& point : body.points)
                arms.push_back(r * point);
            turned = true;
        }
        if (sphere && inShaft) {
            // The point nearest the shaft's wall: on the sphere's equator, away from the axis.
            const dvec3 rho = plane.fromHoleAxis(x);
            const double len = glm::length(rho);
            if (len > 0.0)
                out.emplace_back(-rho / len, rho / len * body.shape.radius,
                                 plane.holeRadius - len - body.shape.radius, shaft, 0);
            continue;
        }
        if (sphere)
            arms.assign(1, -body.shape.radius * plane.normal);
        for (std::size_t k = 0; k < arms.size(); ++k) {
            const dvec3& arm = arms[k];
            const dvec3 at = x + arm;
            if (inShaft) {
                const dvec3 rho = plane.fromHoleAxis(at);
                const double len = glm::length(rho);
                if (len > 0.0)
                    out.emplace_back(-rho / len, arm, plane.holeRadius - len, shaft, int(k));
            } else if (const double gap = plane.distance(at);
                       gap < pointReach && !(plane.holeRadius > 0.0 && plane.overHole(at))) {
                out.emplace_back(plane.normal, arm, gap, int(p), int(k));
            }
        }
    }
}

/// 1 / (1/m + (I^-1 (r x u)) . (r x u)): the mass the point r feels along u.
/// Gauss-Seidel over the contacts, with accumulated impulses, until no impulse changes by more
/// than a part in 1e9 of the largest, or 32 sweeps (a flat landing's four corners need a few
/// dozen to share it evenly; a contact that persists starts from its last step's impulses,
/// applied first, and most need one). Friction first, then the normal impulse, so that the
/// normal constraint (no sinking) is the one met last in each sweep, as Box2D orders them.
void solveImpulses(std::vector<Contact>& contacts, double friction, double inverseMass, const dmat3& inverseInertia,
                   dvec3& v, dvec3& momentum)
{
    dvec3 omega = inverseInertia * momentum;
    const auto apply = [&](const Row& row, double impulse) {
        v += (impulse * inverseMass) * row.u;
        momentum += impulse * row.angular;
        omega += impulse * row.response;
    };
    for (const Contact& c : contacts)
        for (const Row* row : {&c.along, &c.across[0], &c.across[1]})
            apply(*row, row->impulse);
    constexpr int kMaxSweeps = 32;
    for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
        double change = 0.0, largest = 0.0;
        for (Contact& c : contacts) {
            const double limit = friction * c.along.impulse;
            double wanted[2];
            for (int t = 0; t < 2; ++t)
                wanted[t] = c.across[t].impulse - c.across[t].mass * c.across[t].speed(v, omega);
            const double length = std::sqrt(wanted[0] * wanted[0] + wanted[1] * wanted[1]);
            const double scale = length > limit ? limit / length : 1.0;
            for (Row& row : c.across) {
                const double next = wanted[&row - c.across] * scale;
                apply(row, next - row.impulse);
                change = std::max(change, std::abs(next - row.impulse));
                row.impulse = next;
            }
            Row& n = c.along;
            const double next = std::max(n.impulse + n.mass * (c.target - n.speed(v, omega)), 0.0);
            apply(n, next - n.impulse);
            change = std::max(change, std::abs(next - n.impulse));
            n.impulse = next;
            largest = std::max(largest, next);
        }
        if (change <= 1e-9 * largest)
            break;
    }
}

/// Moves the body at its end pose out of every surface a point is still beyond (what the
/// linearised contacts leave: a turning body's points move on arcs), along each surface's
/// normal by its deepest point's gap.
bool pushOut(const ContactBody& body, std::span<const Plane> planes, double radius, RigidState& s)
{
    bool moved = false;
    thread_local std::vector<Contact> end;
    end.clear();
    candidates(body, planes, s.x, glm::mat3_cast(s.rotation.orientation), radius, 0.0, end);
    for (std::size_t surface = 0; surface < 2 * planes.size(); ++surface) {
        const Contact* deepest = nullptr;
        for (const Contact& c : end)
            if (c.surface == int(surface) && c.gap < 0.0 && (!deepest || c.gap < deepest->gap))
                deepest = &c;
        if (deepest) {
            s.x -= deepest->gap * deepest->normal;
            moved = true;
        }
    }
    return moved;
}

/// Of the candidates, the contacts: the points that at the end's velocity (v, omega) would
/// reach their surface within the step, each with the normal speed it should leave with and
/// its three rows set up. Returns whether one bounces.
bool keepArriving(const ContactBody& body, const ContactStep& step, const dvec3& v, const dvec3& omega,
                  const dmat3& inverseInertia, std::vector<Contact>& contacts)
{
    bool bounced = false;
    // A box's points on one surface share its normal, and so its tangents: worked out once (a
    // root and a division), not for every point. Compared bit for bit, so that a -0 component
    // never takes the tangents of a +0.
    dvec3 tangent[2]{dvec3(0.0), dvec3(0.0)}, tangentsFor(0.0);
    bool tangentsKnown = false;
    std::erase_if(contacts, [&](Contact& c) {
        const double arriving = glm::dot(c.normal, v + glm::cross(omega, c.arm));
        if (c.gap + std::min(arriving, 0.0) * step.dt > 0.0 && c.gap > 0.0)
            return true;
        // Faster than resting, it bounces: leaves at e times its arriving speed. Slower, it may
        // close the gap but not cross it (a speculative contact: a body at rest stays at rest,
        // with no velocity that would make it jitter, and no penetration to push it out of).
        const bool bounce = arriving < -step.restingSpeed;
        c.target = bounce ? -body.restitution * arriving : std::max(c.gap, 0.0) / -step.dt;
        c.bounces = bounce;
        bounced = bounced || bounce;
        if (!tangentsKnown || std::memcmp(&c.normal, &tangentsFor, sizeof(dvec3)) != 0) {
            tangentsOf(c.normal, tangent);
            tangentsFor = c.normal;
            tangentsKnown = true;
        }
        c.along.setUp(c.normal, c.arm, body.inertia.inverseMass, inverseInertia);
        for (int t = 0; t < 2; ++t)
            c.across[t].setUp(tangent[t], c.arm, body.inertia.inverseMass, inverseInertia);
        return false;
    });
    return bounced;
}

/// Warm start: a contact that persists (the same point against the same surface) takes the
/// impulses it ended the last step with; a bouncing one starts from none, so that its
/// restitution is not fed by the last step's push. The memory is then empty, for this step's.
void warmStart(RigidBody::ContactMemory& memory, std::vector<Contact>& contacts)
{
    const auto& remembered = memory.impulses;
    for (Contact& c : contacts) {
        if (c.bounces) // told by its flag: with e = 0 its target, +0, equals a resting one's -0
            continue;
        for (std::size_t k = 0; k < memory.count; ++k)
            if (remembered[k].point == c.point && remembered[k].surface == c.surface) {
                c.along.impulse = remembered[k].normal;
                c.across[0].impulse = remembered[k].tangent[0];
                c.across[1].impulse = remembered[k].tangent[1];
            }
    }
    memory.count = 0;
}

/// Solves the contacts (solveImpulses), remembers the pushing ones' impulses for the next
/// step's warm start, and moves the end pose: the impulses act at the start of the step, so it
/// moves by the part of the step's drift that the end velocity drives (driftWeight).
void solveAtStart(const ContactBody& body, const ContactStep& step, const dmat3& inverseInertia,
                  std::vector<Contact>& contacts, RigidState& s)
{
    const dvec3 v0 = s.v, l0 = s.rotation.momentum;
    solveImpulses(contacts, body.friction, body.inertia.inverseMass, inverseInertia, s.v, s.rotation.momentum);
    if (body.memory)
        for (const Contact& c : contacts)
            if (c.along.impulse > 0.0 && body.memory->count < RigidBody::kRememberedContacts)
                body.memory->impulses[body.memory->count++] = {c.point, c.surface, c.along.impulse,
                                                               {c.across[0].impulse, c.across[1].impulse}};
    const double drift = step.driftWeight * step.dt;
    s.x += (s.v - v0) * drift;
    const dvec3 turn = inverseInertia * (s.rotation.momentum - l0);
    s.rotation.orientation =
        glm::normalize(s.rotation.orientation + orientationRate(step.start.rotation.orientation, turn) * drift);
}

/// No contact leaves the body with more energy than it started the step with, or would have
/// ended it with untouched: what the linearised contacts and the push-out would add is taken
/// from its motion (v and L scaled alike).
void capEnergy(const ContactBody& body, const RigidState& start, const RigidState& untouched, RigidState& s)
{
    const double reference = std::max(energyInGravity(start, body.inertia, body.gravity),
                                      energyInGravity(untouched, body.inertia, body.gravity));
    const double excess = energyInGravity(s, body.inertia, body.gravity) - reference;
    if (!(excess > 0.0)) // a NaN too: the finite check names the body
        return;
    const double kinetic = energyInGravity(RigidState{dvec3(0.0), s.v, s.rotation}, body.inertia, body.gravity);
    const double keep = kinetic > excess ? std::sqrt(1.0 - excess / kinetic) : 0.0;
    s.v *= keep;
    s.rotation.momentum *= keep;
    // Too little motion to take it from (a slow bounce, whose linearised contact leaves the
    // body a little higher than its arc would): the body ends that much lower instead.
    const double g2 = glm::dot(body.gravity, body.gravity);
    if (kinetic < excess && g2 > 0.0)
        s.x += body.gravity * ((excess - kinetic) * body.inertia.inverseMass / g2);
}

} // namespace

double driftWeight(Integrator integrator)
{
    switch (integrator) {
    case Integrator::ForwardEuler: return 0.0;
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitGyroscopic: return 1.0;
    case Integrator::VelocityVerlet:
    case Integrator::RK4: return 0.5;
    }
    return 1.0;
}

double energyInGravity(const RigidState& s, const RigidInertia& inertia, const dvec3& gravity)
{
    const double mass = 1.0 / inertia.inverseMass;
    const dvec3 omega = angularVelocity(s.rotation.orientation, inertia.inverseInertiaBody, s.rotation.momentum);
    return 0.5 * mass * glm::dot(s.v, s.v) + 0.5 * glm::dot(omega, s.rotation.momentum) - mass * glm::dot(gravity, s.x);
}

bool resolvePlaneContacts(const ContactBody& body, std::span<const Plane> planes, const ContactStep& step,
                          RigidState& s)
{
    const RigidState& start = step.start;
    const dmat3 r = glm::mat3_cast(start.rotation.orientation);
    const dmat3 inverseInertia = r * body.inertia.inverseInertiaBody * glm::transpose(r);
    const dvec3 omega = inverseInertia * s.rotation.momentum; // the end's, at the start's pose
    // No point moves further in the step than the centre's and the spin's reach.
    const double radius = body.boundingRadius;
    const double reach = (glm::length(s.v) + glm::length(omega) * radius) * step.dt;
    thread_local std::vector<Contact> contacts;
    contacts.clear();
    candidates(body, planes, start.x, r, radius + reach, reach, contacts);
    const bool bounced = keepArriving(body, step, s.v, omega, inverseInertia, contacts);
    if (body.memory)
        warmStart(*body.memory, contacts);
    const RigidState untouched = s;
    if (!contacts.empty())
        solveAtStart(body, step, inverseInertia, contacts, s);
    // The contacts' prediction is exact for a body that moves its whole drift with the end's
    // velocity (semi-implicit Euler) and does not turn: then, and while the turn's arc departs
    // from the straight line by less than a picometre, the end pose needs no second look.
    const double spin = glm::length(inverseInertia * s.rotation.momentum);
    const bool straight = step.driftWeight == 1.0 && 0.5 * spin * spin * radius * step.dt * step.dt < 1e-12;
    const bool pushed = !straight && pushOut(body, planes, radius, s);
    if (!pushed && contacts.empty())
        return bounced; // untouched: nothing to check (most bodies in flight)
    capEnergy(body, start, untouched, s);
    return bounced;
}

} // namespace pba
