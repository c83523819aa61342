// The contact solver's rows, pass 2 (the velocity sweeps, warm-started) and a huge island's
// halves; pass 1 is in collision_pass.cpp, pass 3 in position_pass.cpp.
#include "rigid/contact_solver.hpp"

#include <algorithm>
#include <cmath>

namespace pba::rigid {

namespace {

Jacobian jacobianOf(const SolverBody& a, const SolverBody& b, const dvec3& ra, const dvec3& rb, const dvec3& u)
{
    const dvec3 momentA = glm::cross(ra, u), momentB = glm::cross(rb, u);
    const dvec3 turnA = a.inverseInertia * momentA, turnB = b.inverseInertia * momentB;
    const double k = a.inverseMass + b.inverseMass + glm::dot(momentA, turnA) + glm::dot(momentB, turnB);
    return {glm::vec3(u), glm::vec3(momentA), glm::vec3(momentB), glm::vec3(turnA), glm::vec3(turnB),
            float(k > 0.0 ? 1.0 / k : 0.0)};
}

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
    m_positionRowsBuilt = false; // the last island's
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
            // A gap may close, no more (a speculative contact): resting stays at rest, and an
            // arrival slower than the resting speed lands without a bounce. The end velocity
            // moves a body by one step's drift in all (its integrator's share of this step's and
            // the rest of the next's), after the start velocity's share of this one (none for
            // semi-implicit Euler, all for forward Euler): a body settling onto a contact may
            // close only the gap that share leaves. (A faster arrival is the collision pass's; a
            // contact opening keeps the start's gap, so that closing again is no faster.)
            const dvec3 lagged = b.pointStartVelocity(r.rB) * (1.0 - b.driftWeight) -
                                 a.pointStartVelocity(r.rA) * (1.0 - a.driftWeight);
            const double lag = glm::dot(r.n, lagged);
            const bool settling = lag <= 0.0 && lag >= -m_settings.restingSpeed;
            const double gap = r.separation + (settling ? lag * m_settings.dt : 0.0);
            v.target = -std::max(gap, 0.0) / m_settings.dt;
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
        finishVelocities();
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
    finishVelocities();
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

void ContactSolver::markVelocities(std::span<const std::uint32_t> bodies)
{
    for (const std::uint32_t k : bodies) {
        m_marks[2 * k] = m_bodies[k].v;
        m_marks[2 * k + 1] = m_bodies[k].w;
    }
}

} // namespace pba::rigid
