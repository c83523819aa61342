#include "rigid/contact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace pba::rigid {

namespace {

/// 1 / (1/mA + 1/mB + (rA x u) . IA^-1 (rA x u) + (rB x u) . IB^-1 (rB x u)): the mass the two
/// points feel along u; 0 between two static bodies.
double effectiveMass(const SolverBody& a, const SolverBody& b, const dvec3& ra, const dvec3& rb, const dvec3& u)
{
    const dvec3 ca = glm::cross(ra, u), cb = glm::cross(rb, u);
    const double k = a.inverseMass + b.inverseMass + glm::dot(ca, a.inverseInertia * ca) +
                     glm::dot(cb, b.inverseInertia * cb);
    return k > 0.0 ? 1.0 / k : 0.0;
}

dvec3 relativeVelocity(const SolverBody& a, const SolverBody& b, const PointRows& r)
{
    return b.pointVelocity(r.rB) - a.pointVelocity(r.rA);
}

/// The impulse p on B at its arm, and its opposite on A at A's.
void applyPair(SolverBody& a, SolverBody& b, const PointRows& r, const dvec3& p)
{
    a.applyImpulse(-p, r.rA);
    b.applyImpulse(p, r.rB);
}

Jacobian jacobianOf(const SolverBody& a, const SolverBody& b, const dvec3& ra, const dvec3& rb, const dvec3& u)
{
    const dvec3 momentA = glm::cross(ra, u), momentB = glm::cross(rb, u);
    const dvec3 turnA = a.inverseInertia * momentA, turnB = b.inverseInertia * momentB;
    const double k = a.inverseMass + b.inverseMass + glm::dot(momentA, turnA) + glm::dot(momentB, turnB);
    return {glm::vec3(u), glm::vec3(momentA), glm::vec3(momentB), glm::vec3(turnA), glm::vec3(turnB),
            float(k > 0.0 ? 1.0 / k : 0.0)};
}

/// The two points' relative speed along a row.
double speedAlong(const Jacobian& j, const SolverBody& a, const SolverBody& b)
{
    return glm::dot(dvec3(j.u), b.v - a.v) + glm::dot(dvec3(j.momentB), b.w) - glm::dot(dvec3(j.momentA), a.w);
}

/// An impulse `lambda` along a row: on B, and its opposite on A (a static body untouched: the
/// islands that touch one share it).
void applyAlong(const Jacobian& j, double lambda, SolverBody& a, SolverBody& b)
{
    if (!a.isStatic()) {
        a.v -= (lambda * a.inverseMass) * dvec3(j.u);
        a.w -= lambda * dvec3(j.turnA);
    }
    if (!b.isStatic()) {
        b.v += (lambda * b.inverseMass) * dvec3(j.u);
        b.w += lambda * dvec3(j.turnB);
    }
}

/// The smallest s in [0, span] at which gap + u s + a s^2 / 2 reaches 0, or NaN if it does not
/// within the span. A gap already closed is reached at once.
double arrival(double gap, double u, double a, double span)
{
    if (gap <= 0.0)
        return 0.0;
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    if (a == 0.0)
        return u < 0.0 && -gap / u <= span ? -gap / u : nan;
    const double disc = u * u - 2.0 * a * gap;
    if (disc < 0.0)
        return nan;
    // The smaller positive root of a s^2 / 2 + u s + gap, in the form that does not cancel.
    const double q = -(u + std::copysign(std::sqrt(disc), u));
    double s1 = q / a, s2 = q != 0.0 ? 2.0 * gap / q : nan;
    double s = std::numeric_limits<double>::infinity();
    for (double root : {s1, s2})
        if (root >= 0.0 && root < s)
            s = root;
    return s <= span ? s : nan;
}

constexpr int kMaxPoints = contact::Manifold::kMaxPoints;
constexpr int kMaxCollisionSweeps = 16;

constexpr int kMaxImpactSweeps = 32;
/// A sweep that changes no impulse by more than this share of the largest has converged.
constexpr double kConverged = 1e-6;

} // namespace

void tangentsOf(const dvec3& n, dvec3 (&t)[2])
{
    const dvec3 other = std::abs(n.x) < 0.57735 ? dvec3(1.0, 0.0, 0.0) : dvec3(0.0, 1.0, 0.0);
    t[0] = glm::normalize(glm::cross(n, other));
    t[1] = glm::cross(n, t[0]);
}

void ContactSolver::prepare(std::span<Contact> contacts, std::span<const std::uint32_t> island,
                            std::span<const std::uint32_t> moving, std::span<SolverBody> bodies,
                            const SolverSettings& settings, bool withJoints)
{
    m_moving = moving;
    m_contacts = contacts;
    m_bodies = bodies;
    m_settings = settings;
    m_constraints.clear();
    std::uint32_t rows = 0;
    for (const std::uint32_t index : island) {
        const Contact& contact = contacts[index];
        m_constraints.push_back({index, contact.a, contact.b, contact.friction, contact.restitution, contact.radiusA,
                                 contact.radiusB, rows, contact.count});
        rows += std::uint32_t(contact.count);
    }
    m_rows.resize(rows);
    m_velocityRows.resize(rows);
    if (m_marks.size() < 2 * bodies.size())
        m_marks.resize(2 * bodies.size());
    m_halved = !withJoints && m_constraints.size() >= kHalvedContacts;
    if (!m_halved) {
        prepareRows(m_constraints);
        return;
    }
    halve();
    runHalves(1, [&](int, Half half) {
        prepareRows(part(half).constraints);
        return true;
    });
}

void ContactSolver::prepareRows(std::span<const IslandContact> constraints)
{
    for (const IslandContact& c : constraints) {
        const Contact& contact = m_contacts[c.contact];
        const SolverBody& a = m_bodies[c.a];
        const SolverBody& b = m_bodies[c.b];
        for (int i = 0; i < c.count; ++i) {
            const ContactPoint& p = contact.points[i];
            PointRows& r = m_rows[c.first + i];
            r = PointRows{};
            r.rA = p.point - a.position;
            r.rB = p.point - b.position;
            r.n = p.normal;
            tangentsOf(r.n, r.t);
            VelocityRows& v = m_velocityRows[c.first + i];
            v.along = jacobianOf(a, b, r.rA, r.rB, r.n);
            for (int k = 0; k < 2; ++k)
                v.across[k] = jacobianOf(a, b, r.rA, r.rB, r.t[k]);
            r.separation = p.separation;
            const dvec3 start = b.pointStartVelocity(r.rB) - a.pointStartVelocity(r.rA);
            const dvec3 free = relativeVelocity(a, b, r);
            r.vnStart = glm::dot(r.n, start);
            r.vnFree = glm::dot(r.n, free);
            for (int k = 0; k < 2; ++k) {
                r.vtStart[k] = glm::dot(r.t[k], start);
                r.vtFree[k] = glm::dot(r.t[k], free);
            }
            v.normalImpulse = p.normalImpulse;
            v.tangentImpulse[0] = p.tangentImpulse[0];
            v.tangentImpulse[1] = p.tangentImpulse[1];
            // A gap may close within the step, no more (a speculative contact): resting stays at
            // rest, and an arrival slower than the resting speed lands without a bounce.
            v.target = -std::max(r.separation, 0.0) / m_settings.dt;
        }
    }
}

void ContactSolver::halve()
{
    for (const std::uint32_t k : m_sided)
        m_side[k] = -1;
    m_sided.assign(m_moving.begin(), m_moving.end());
    if (m_side.size() < m_bodies.size())
        m_side.resize(m_bodies.size(), -1);
    dvec3 lo(INFINITY), hi(-INFINITY);
    for (const std::uint32_t k : m_moving) {
        lo = glm::min(lo, m_bodies[k].position);
        hi = glm::max(hi, m_bodies[k].position);
    }
    // At the median along the longest side of the island's box: two halves of as many bodies,
    // and the fewest contacts across the cut a plane gives (the body's index breaks a tie).
    const dvec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    m_along.clear();
    for (const std::uint32_t k : m_sided)
        m_along.emplace_back(m_bodies[k].position[axis], k);
    const auto middle = m_along.begin() + std::ptrdiff_t(m_along.size() / 2);
    std::nth_element(m_along.begin(), middle, m_along.end());
    for (Part& p : m_parts)
        p.bodies.clear();
    for (auto it = m_along.begin(); it != m_along.end(); ++it) {
        const bool second = it >= middle;
        m_side[it->second] = second ? 1 : 0;
        part(second ? Half::Second : Half::First).bodies.push_back(it->second);
    }
    // The contacts in three runs, one a part, each in the island's order: a part's are a span.
    std::size_t at[3] = {0, 0, 0};
    for (const IslandContact& c : m_constraints)
        ++at[std::size_t(halfOf(m_side[c.a], m_side[c.b]))];
    at[2] = at[0] + at[1];
    at[1] = at[0];
    at[0] = 0;
    for (std::size_t h = 0; h < 3; ++h)
        m_parts[h].first = std::uint32_t(at[h]);
    m_byPart.resize(m_constraints.size());
    for (const IslandContact& c : m_constraints)
        m_byPart[at[std::size_t(halfOf(m_side[c.a], m_side[c.b]))]++] = c;
    m_constraints.swap(m_byPart);
    for (std::size_t h = 0; h < 3; ++h)
        m_parts[h].constraints = std::span<const IslandContact>(m_constraints).subspan(m_parts[h].first,
                                                                                        at[h] - m_parts[h].first);
}

void ContactSolver::startCollisions()
{
    // A contact that found no arrival finds none again until one of its bodies is struck: each
    // body counts its blows, and a contact is looked at again only when the counts it last saw
    // have changed (the sweeps' results are those of looking at every contact every sweep).
    if (m_blows.size() < m_bodies.size())
        m_blows.resize(m_bodies.size());
    for (const IslandContact& c : m_constraints)
        m_blows[c.a] = m_blows[c.b] = 0;
    m_seen.assign(m_constraints.size(), ~std::uint64_t(0));
    m_strikes.assign(m_constraints.size(), 0);
}

bool ContactSolver::collide(int maxStrikes)
{
    startCollisions();
    bool any = false;
    for (int sweep = 0; sweep < kMaxCollisionSweeps; ++sweep) {
        bool changed = false;
        for (std::size_t k = 0; k < m_constraints.size(); ++k)
            changed = lookForBlow(k, maxStrikes) || changed;
        if (!changed)
            break;
        any = true;
    }
    markVelocities(m_moving);
    return any;
}

void ContactSolver::markVelocities(std::span<const std::uint32_t> bodies)
{
    for (const std::uint32_t k : bodies) {
        m_marks[2 * k] = m_bodies[k].v;
        m_marks[2 * k + 1] = m_bodies[k].w;
    }
}

bool ContactSolver::lookForBlow(std::size_t k, int maxStrikes)
{
    const IslandContact& c = m_constraints[k];
    const std::uint64_t blows = (std::uint64_t(m_blows[c.a]) << 32) | m_blows[c.b];
    if (blows == m_seen[k] || m_strikes[k] >= maxStrikes)
        return false;
    m_seen[k] = blows;
    if (!collideOne(c))
        return false;
    ++m_strikes[k];
    for (const BodyIndex body : {c.a, c.b})
        if (!m_bodies[body].isStatic()) // a static body never changes (and is shared)
            ++m_blows[body];
    return true;
}

ContactSolver::SurfacePoints ContactSolver::surfacePoints(double radiusA, double radiusB, const ContactPoint& p,
                                                         const dvec3& xa, const dmat3& ra, const dvec3& xb,
                                                         const dmat3& rb)
{
    SurfacePoints s;
    s.n = p.normal;
    if (radiusA > 0.0 && radiusB > 0.0) {
        // Two spheres touch along the line of their centres, wherever that has turned.
        const dvec3 d = xb - xa;
        if (const double len = glm::length(d); len > 0.0)
            s.n = d / len;
    }
    s.a = radiusA > 0.0 ? xa + radiusA * s.n : xa + ra * p.anchorA;
    s.b = radiusB > 0.0 ? xb - radiusB * s.n : xb + rb * p.anchorB;
    return s;
}

double ContactSolver::restitutionOf(const IslandContact& c, const PointRows& r) const
{
    // A method of order one does not keep the energy of a fall, but a modified one: along the
    // normal, with gap s, speed u and constant acceleration a, forward Euler keeps exactly
    // Q = u^2/2 - a s - a dt u / 2 and semi-implicit Euler Q = u^2/2 - a s + a dt u / 2 (velocity
    // Verlet and RK4 the energy itself), that is Q = u^2/2 - a s + (w - 1/2) a dt u with w the
    // method's drift weight. Its apex is where u = 0, at s = -Q/a. Leaving with the speed that
    // gives Q' = e^2 Q, rather than e times the speed of the exact arrival, makes the method's
    // own rebound reach e^2 times the height it fell from: the exact arrival would leave its
    // O(dt) error of the fall and of the rise in the bounce (3.7% each way for a 1 m drop at 60 Hz).
    // Returned as the ratio of that speed to the exact arrival's along the start's normal, which
    // is e itself where the acceleration along the normal is nil (two bodies both falling).
    const SolverBody& a = m_bodies[c.a];
    const SolverBody& b = m_bodies[c.b];
    const double dt = m_settings.dt;
    const double accel = (r.vnFree - r.vnStart) / dt;
    const double mass = a.inverseMass + b.inverseMass;
    const double w = mass > 0.0 ? (a.driftWeight * a.inverseMass + b.driftWeight * b.inverseMass) / mass : 1.0;
    const double k = (w - 0.5) * accel * dt;
    const double q = 0.5 * r.vnStart * r.vnStart - accel * std::max(r.separation, 0.0) + k * r.vnStart;
    const double e2q = c.restitution * c.restitution * q;
    const double exact2 = r.vnStart * r.vnStart - 2.0 * accel * std::max(r.separation, 0.0);
    if (k == 0.0 || !(k * k + 2.0 * e2q >= 0.0) || !(exact2 > m_settings.restingSpeed * m_settings.restingSpeed))
        return c.restitution;
    // An O(dt) correction of e: never past the bounds a restitution has.
    return std::clamp((-k + std::sqrt(k * k + 2.0 * e2q)) / std::sqrt(exact2), 0.0, 1.0);
}

double ContactSolver::refineArrival(const IslandContact& c, int point, double tPrev, double tau) const
{
    // The estimate took the gap along the start's normal as changing at a constant rate; along
    // the free paths themselves (turning, and off-centre for two spheres) it closes a little
    // sooner or later. Newton's method on the gap between the two surface points, a few times.
    const SolverBody& a = m_bodies[c.a];
    const SolverBody& b = m_bodies[c.b];
    const double dt = m_settings.dt;
    const ContactPoint& p = m_contacts[c.contact].points[point];
    for (int k = 0; k < 8; ++k) {
        const double f = tau / dt;
        const dvec3 xa = a.freePosition(f, dt), xb = b.freePosition(f, dt);
        const SurfacePoints sp = surfacePoints(c.radiusA, c.radiusB, p, xa, glm::mat3_cast(a.freeOrientation(f)), xb,
                                               glm::mat3_cast(b.freeOrientation(f)));
        const double gap = glm::dot(sp.b - sp.a, sp.n);
        const dvec3 u = b.velocityAt(f) + glm::cross(b.spinAt(f), sp.b - xb) - a.velocityAt(f) -
                        glm::cross(a.spinAt(f), sp.a - xa);
        const double closing = glm::dot(u, sp.n);
        if (!(closing < 0.0))
            break;
        const double next = std::clamp(tau - gap / closing, tPrev, dt);
        if (std::abs(next - tau) <= 1e-15 * dt)
            break;
        tau = next;
    }
    return tau;
}

bool ContactSolver::firstArrival(const IslandContact& c, double& tau, bool (&arrives)[kMaxPoints]) const
{
    // When each point arrives: its gap moves with the start's velocities up to the last impulse
    // either body took this step (tPrev), and from then with the present ones, the free step's
    // acceleration taken as constant throughout.
    const SolverBody& a = m_bodies[c.a];
    const SolverBody& b = m_bodies[c.b];
    const double dt = m_settings.dt;
    const double tPrev = std::max(a.lastImpact, b.lastImpact);
    tau = dt;
    bool any = false;
    int first = 0;
    for (int i = 0; i < c.count; ++i) {
        const PointRows& r = m_rows[c.first + i];
        const double accel = (r.vnFree - r.vnStart) / dt;
        const double vn = glm::dot(r.n, relativeVelocity(a, b, r));
        const double gap = r.separation + r.vnStart * tPrev + 0.5 * accel * tPrev * tPrev;
        const double speed = vn - accel * (dt - tPrev);
        const double s = arrival(gap, speed, accel, dt - tPrev);
        if (std::isnan(s) || !(speed + accel * s < -m_settings.restingSpeed))
            continue;
        arrives[i] = true;
        if (tPrev + s < tau) {
            tau = tPrev + s;
            first = i;
        }
        any = true;
    }
    if (any)
        tau = refineArrival(c, first, tPrev, tau);
    return any;
}

int ContactSolver::impactRows(const IslandContact& c, double tau, const bool (&arrives)[kMaxPoints],
                              ImpactRow (&rows)[kMaxPoints]) const
{
    // The impulses act at tau, at the points where the bodies' free paths had them then, both
    // bodies' arms reaching one point: so they change the total momentum and angular momentum by
    // nothing, and the energy by exactly what restitution and friction take.
    const SolverBody& a = m_bodies[c.a];
    const SolverBody& b = m_bodies[c.b];
    const double f = tau / m_settings.dt;
    const dvec3 xa = a.freePosition(f, m_settings.dt), xb = b.freePosition(f, m_settings.dt);
    const dmat3 qa = glm::mat3_cast(a.freeOrientation(f)), qb = glm::mat3_cast(b.freeOrientation(f));
    const dvec3 va = a.velocityAt(f), wa = a.spinAt(f), vb = b.velocityAt(f), wb = b.spinAt(f);
    int count = 0;
    for (int i = 0; i < c.count; ++i) {
        if (!arrives[i])
            continue;
        const SurfacePoints sp = surfacePoints(c.radiusA, c.radiusB, m_contacts[c.contact].points[i], xa, qa, xb, qb);
        ImpactRow& row = rows[count];
        // A sphere touches at its own surface point on the normal, exactly: the other shape's
        // point was found at the start, and a sphere sliding in across a face has moved on since
        // (their midpoint would lever the sphere into a spin no frictionless contact gives).
        const bool sphereA = c.radiusA > 0.0, sphereB = c.radiusB > 0.0;
        const dvec3 p = sphereA && !sphereB ? sp.a : sphereB && !sphereA ? sp.b : 0.5 * (sp.a + sp.b);
        row.point = i;
        row.rows.rA = p - xa;
        row.rows.rB = p - xb;
        row.rows.n = sp.n;
        tangentsOf(sp.n, row.rows.t);
        row.rows.normalMass = effectiveMass(a, b, row.rows.rA, row.rows.rB, sp.n);
        const dvec3 atImpact = vb + glm::cross(wb, row.rows.rB) - va - glm::cross(wa, row.rows.rA);
        const double arriving = glm::dot(sp.n, atImpact);
        if (!(arriving < -m_settings.restingSpeed))
            continue; // it meets the surface turning away from it
        const dvec3 now = relativeVelocity(a, b, row.rows);
        // The method's own energy describes a fall from the start of the step, not an arrival that
        // an earlier blow in this step set off: then the restitution is e itself.
        const bool ownFall = !a.struck && !b.struck;
        const double leaving = -arriving * (ownFall ? restitutionOf(c, m_rows[c.first + i]) : c.restitution);
        row.targetN = glm::dot(sp.n, now) + (leaving - arriving);
        for (int k = 0; k < 2; ++k) {
            row.rows.tangentMass[k] = effectiveMass(a, b, row.rows.rA, row.rows.rB, row.rows.t[k]);
            row.targetT[k] = glm::dot(row.rows.t[k], now - atImpact); // its sliding at arrival stopped
        }
        ++count;
    }
    return count;
}

void ContactSolver::solveImpact(const IslandContact& c, std::span<ImpactRow> rows)
{
    // The arriving points' impulses together, to convergence: each leaves at e times its
    // arriving speed, and slides no faster than friction lets it.
    SolverBody& a = m_bodies[c.a];
    SolverBody& b = m_bodies[c.b];
    for (int sweep = 0; sweep < kMaxImpactSweeps; ++sweep) {
        double change = 0.0, largest = 0.0;
        for (ImpactRow& row : rows) {
            const PointRows& r = row.rows;
            double want[2];
            for (int k = 0; k < 2; ++k)
                want[k] = row.pushT[k] - r.tangentMass[k] * (glm::dot(r.t[k], relativeVelocity(a, b, r)) - row.targetT[k]);
            const double length = std::sqrt(want[0] * want[0] + want[1] * want[1]);
            const double limit = c.friction * row.pushN;
            const double scale = length > limit ? limit / length : 1.0;
            for (int k = 0; k < 2; ++k) {
                const double next = want[k] * scale;
                applyPair(a, b, r, (next - row.pushT[k]) * r.t[k]);
                change = std::max(change, std::abs(next - row.pushT[k]));
                row.pushT[k] = next;
            }
            const double vn = glm::dot(r.n, relativeVelocity(a, b, r));
            const double next = std::max(row.pushN - r.normalMass * (vn - row.targetN), 0.0);
            applyPair(a, b, r, (next - row.pushN) * r.n);
            change = std::max(change, std::abs(next - row.pushN));
            row.pushN = next;
            largest = std::max(largest, next);
        }
        if (change <= 1e-12 * largest)
            break;
    }
}

bool ContactSolver::collideOne(const IslandContact& c)
{
    double tau = 0.0;
    bool arrives[kMaxPoints] = {};
    if (!firstArrival(c, tau, arrives))
        return false;
    ImpactRow rows[kMaxPoints];
    const int count = impactRows(c, tau, arrives, rows);
    if (count == 0)
        return false;
    SolverBody& a = m_bodies[c.a];
    SolverBody& b = m_bodies[c.b];
    const dvec3 va0 = a.v, wa0 = a.w, vb0 = b.v, wb0 = b.w;
    solveImpact(c, std::span(rows, std::size_t(count)));
    // The end poses move by the velocity change over what is left of the step.
    const double left = m_settings.dt - tau;
    const auto shift = [&](SolverBody& body, const dvec3& v0, const dvec3& w0) {
        if (body.isStatic())
            return;
        body.shift += (body.v - v0) * left;
        body.turn += (body.w - w0) * left;
        body.lastImpact = tau;
        body.struck = true;
    };
    shift(a, va0, wa0);
    shift(b, vb0, wb0);
    for (int i = 0; i < count; ++i) {
        m_rows[c.first + rows[i].point].bounced = true;
        VelocityRows& v = m_velocityRows[c.first + rows[i].point];
        v.normalImpulse = 0.0; // its warm start was a resting push: not for a bounce
        v.tangentImpulse[0] = v.tangentImpulse[1] = 0.0;
    }
    return true;
}

void ContactSolver::warmStart(std::span<const IslandContact> constraints)
{
    for (const IslandContact& c : constraints) {
        SolverBody& a = m_bodies[c.a];
        SolverBody& b = m_bodies[c.b];
        for (int i = 0; i < c.count; ++i) {
            const VelocityRows& r = m_velocityRows[c.first + i];
            applyAlong(r.along, r.normalImpulse, a, b);
            applyAlong(r.across[0], r.tangentImpulse[0], a, b);
            applyAlong(r.across[1], r.tangentImpulse[1], a, b);
        }
    }
}

void ContactSolver::warmStart()
{
    warmStart(m_constraints);
    m_wide.colour(m_constraints, m_bodies);
    m_wide.build(m_constraints, m_velocityRows, m_bodies, m_oneAtATime);
}

void ContactSolver::solveFriction(const IslandContact& c, SolverBody& a, SolverBody& b, double& change)
{
    for (int i = 0; i < c.count; ++i) {
        VelocityRows& r = m_velocityRows[c.first + i];
        double want[2];
        for (int k = 0; k < 2; ++k)
            want[k] = r.tangentImpulse[k] - r.across[k].mass * speedAlong(r.across[k], a, b);
        const double length = std::sqrt(want[0] * want[0] + want[1] * want[1]);
        const double limit = c.friction * r.normalImpulse;
        const double scale = length > limit ? limit / length : 1.0;
        for (int k = 0; k < 2; ++k) {
            const double next = want[k] * scale;
            applyAlong(r.across[k], next - r.tangentImpulse[k], a, b);
            change = std::max(change, std::abs(next - r.tangentImpulse[k]));
            r.tangentImpulse[k] = next;
        }
    }
}

void ContactSolver::solveNormal(const IslandContact& c, SolverBody& a, SolverBody& b, double& change, double& largest)
{
    for (int i = 0; i < c.count; ++i) {
        VelocityRows& r = m_velocityRows[c.first + i];
        const double next = std::max(r.normalImpulse - r.along.mass * (speedAlong(r.along, a, b) - r.target), 0.0);
        applyAlong(r.along, next - r.normalImpulse, a, b);
        change = std::max(change, std::abs(next - r.normalImpulse));
        largest = std::max(largest, next);
        r.normalImpulse = next;
    }
}

bool ContactSolver::solveVelocities()
{
    m_change = m_largest = 0.0;
    m_wide.sweep(m_bodies, m_change, m_largest);
    for (const std::uint32_t k : m_oneAtATime) {
        const IslandContact& c = m_constraints[k];
        solveFriction(c, m_bodies[c.a], m_bodies[c.b], m_change);
        solveNormal(c, m_bodies[c.a], m_bodies[c.b], m_change, m_largest);
    }
    return m_change <= kConverged * m_largest;
}

void ContactSolver::sweep(Part& p)
{
    p.change = p.largest = 0.0;
    p.wide.sweep(m_bodies, p.change, p.largest);
    for (const std::uint32_t k : p.oneAtATime) {
        const IslandContact& c = p.constraints[k];
        solveFriction(c, m_bodies[c.a], m_bodies[c.b], p.change);
        solveNormal(c, m_bodies[c.a], m_bodies[c.b], p.change, p.largest);
    }
}

void ContactSolver::solveVelocities(int maxStrikes, int least, int most)
{
    if (!m_halved) {
        collide(maxStrikes);
        warmStart();
        for (int it = 0; it < most; ++it)
            if (solveVelocities() && it + 1 >= least)
                break;
        return;
    }
    // The three passes in one run of rounds: the other core, once it has joined, stays (waking
    // it for each pass took longer than the warm start).
    startCollisions();
    enum class Pass { Collisions, WarmStart, Sweeps };
    Pass pass = Pass::Collisions;
    int first = 0; // the round the pass began in: the pass's variables are the Across job's
    runHalves(kMaxCollisionSweeps + 1 + most, [&](int round, Half half) {
        Part& p = part(half);
        const bool across = half == Half::Across;
        switch (pass) {
        case Pass::Collisions:
            p.struck = false;
            for (std::size_t k = p.first; k < p.first + p.constraints.size(); ++k)
                p.struck = lookForBlow(k, maxStrikes) || p.struck;
            if (across && (!(m_parts[0].struck || m_parts[1].struck || p.struck) ||
                           round + 1 - first == kMaxCollisionSweeps)) {
                pass = Pass::WarmStart;
                first = round + 1;
            }
            return true;
        case Pass::WarmStart:
            markVelocities(p.bodies);
            warmStart(p.constraints);
            p.wide.colour(p.constraints, m_bodies);
            p.wide.build(p.constraints, m_velocityRows, m_bodies, p.oneAtATime);
            if (across) {
                pass = Pass::Sweeps;
                first = round + 1;
            }
            return true;
        case Pass::Sweeps:
            break;
        }
        sweep(p);
        if (!across)
            return true;
        m_change = m_largest = 0.0;
        for (const Part& q : m_parts) {
            m_change = std::max(m_change, q.change);
            m_largest = std::max(m_largest, q.largest);
        }
        const int sweeps = round + 1 - first;
        return !(m_change <= kConverged * m_largest && sweeps >= least) && sweeps < most;
    });
}

void ContactSolver::storeImpulses()
{
    if (m_halved)
        for (const Part& p : m_parts)
            p.wide.storeImpulses(m_velocityRows);
    else
        m_wide.storeImpulses(m_velocityRows);
    for (const IslandContact& c : m_constraints) {
        Contact& contact = m_contacts[c.contact];
        for (int i = 0; i < c.count; ++i) {
            const VelocityRows& r = m_velocityRows[c.first + i];
            ContactPoint& p = contact.points[i];
            p.normalImpulse = r.normalImpulse;
            p.tangentImpulse[0] = r.tangentImpulse[0];
            p.tangentImpulse[1] = r.tangentImpulse[1];
            p.bounced = m_rows[c.first + i].bounced;
        }
    }
}


void ContactSolver::positionRows(std::span<const Contact> contacts)
{
    // A halved island's part by part, each part's in its contacts' order.
    const auto halfOfContact = [&](const Contact& c) {
        if (!m_halved)
            return std::size_t(0);
        const auto side = [&](BodyIndex k) { return k < m_side.size() ? int(m_side[k]) : -1; };
        return std::size_t(halfOf(side(c.a), side(c.b)));
    };
    std::fill(std::begin(m_partRows), std::end(m_partRows), std::size_t(0));
    for (const Contact& c : contacts)
        m_partRows[halfOfContact(c) + 1] += std::size_t(c.count);
    for (std::size_t h = 0; h < 3; ++h)
        m_partRows[h + 1] += m_partRows[h];
    m_positionRows.resize(m_partRows[3]);
    std::size_t fill[3] = {m_partRows[0], m_partRows[1], m_partRows[2]};
    for (const Contact& c : contacts) {
        const SolverBody& a = m_bodies[c.a];
        const SolverBody& b = m_bodies[c.b];
        const dmat3 ra = glm::mat3_cast(a.endOrientation), rb = glm::mat3_cast(b.endOrientation);
        std::size_t& next = fill[halfOfContact(c)];
        for (int i = 0; i < c.count; ++i) {
            const ContactPoint& p = c.points[i];
            m_positionRows[next++] = {c.a, c.b, a.inverseMass + b.inverseMass, p.normal, c.radiusA, c.radiusB,
                                      ra * p.anchorA, rb * p.anchorB};
        }
    }
}

void ContactSolver::solvePositions(std::span<const Contact> contacts)
{
    positionRows(contacts); // the joints' sweeps turn the bodies between the contacts'
    for (const PositionRow& row : m_positionRows)
        solvePosition(row);
}

void ContactSolver::solvePositions(std::span<const Contact> contacts, int sweeps)
{
    // Without joints nothing turns a body in this pass: each point's arms are turned once, and a
    // sweep only adds them to the moving centres.
    positionRows(contacts);
    const auto sweep = [&](std::size_t h) {
        for (std::size_t r = m_partRows[h]; r < m_partRows[h + 1]; ++r)
            solvePosition(m_positionRows[r]);
    };
    if (!m_halved) {
        for (int it = 0; it < sweeps; ++it)
            sweep(0);
        return;
    }
    runHalves(sweeps, [&](int, Half half) {
        sweep(std::size_t(half));
        return true;
    });
}

void ContactSolver::solvePosition(const PositionRow& row)
{
    if (row.k == 0.0)
        return;
    SolverBody& a = m_bodies[row.a];
    SolverBody& b = m_bodies[row.b];
    // The normal is held as it was found (as Box2D holds it through its substeps), but for two
    // spheres: the bodies turn little within a sweep. The surface points as surfacePoints has them.
    dvec3 n = row.n;
    if (row.radiusA > 0.0 && row.radiusB > 0.0) {
        const dvec3 d = b.endPosition - a.endPosition;
        if (const double len = glm::length(d); len > 0.0)
            n = d / len;
    }
    const dvec3 pa = row.radiusA > 0.0 ? a.endPosition + row.radiusA * n : a.endPosition + row.armA;
    const dvec3 pb = row.radiusB > 0.0 ? b.endPosition - row.radiusB * n : b.endPosition + row.armB;
    const SolverSettings& s = m_settings;
    const double separation = glm::dot(pb - pa, n);
    const double correction = std::clamp(s.contact.baumgarte * (separation + s.contact.linearSlop), -s.maxCorrection, 0.0);
    if (correction == 0.0)
        return;
    // Apart along the normal, without turning: a turn about one point of a manifold (an edge
    // crossing an edge has only one) digs another corner in, which this manifold, found before
    // the sweeps, does not hold.
    const dvec3 push = (-correction / row.k) * n;
    if (!a.isStatic())
        a.endPosition -= push * a.inverseMass;
    if (!b.isStatic())
        b.endPosition += push * b.inverseMass;
}

} // namespace pba::rigid
