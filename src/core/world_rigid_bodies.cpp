// A World's phase for its rigid bodies (stepRigidBodies): each awake body's free step under
// every force, one system per integrator, around the rigid system's contacts (src/core/rigid/),
// and the end states written back into the bodies.
#include "pba/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "parallel.hpp"
#include "rigid/rigid_system.hpp"
#include "particle_systems/spring_neighbours.hpp"
#include "world_checks.hpp"

namespace pba {

namespace {

/// Whether q is the unit quaternion every rigid step ends with. One whose components overflow
/// when squared normalises to zero (a spin of 1e200 rad/s turns it by that much a step) and one
/// that is not finite to NaN: either is a blow-up, not an orientation.
bool isUnit(const dquat& q)
{
    return std::abs(glm::length(q) - 1.0) < 1e-3; // false for NaN
}

} // namespace

void World::stepRigidBodies(double dt)
{
    rigid::RigidSystem& system = *m_rigid.system;
    if (system.size() == 0)
        return;
    joinPointBodies();
    givePieces();
    thread_local std::vector<const RigidBody*> bodies;
    bodies.resize(system.size());
    for (std::size_t k = 0; k < system.size(); ++k)
        bodies[k] = system.isPoint(k) ? nullptr
                                      : static_cast<const RigidBody*>(m_bodies.objects[system.worldIndex(k)].get());
    system.begin(bodies);
    givePointBodies();
    integrateRigidFreely(system.awake(), dt);
    m_rigid.endPushes.clear();
    system.findContacts(m_surfaces.planes, dt);
    integrateRigidFreely(system.woken(), dt); // touched by an awake body: they move this step too
    system.solve(gravity(), dt);
    storeRigidBodies();
    storePointBodies();
}

void World::joinPointBodies()
{
    // Looked at again only when bodies were added: a particle takes part from the first step
    // after it has a radius and the world has a rigid body.
    if (m_rigid.bodiesSeen == m_bodies.objects.size())
        return;
    m_rigid.bodiesSeen = m_bodies.objects.size();
    if (!hasRigidBodies())
        return;
    for (std::size_t i = 0; i < m_bodies.objects.size(); ++i) {
        if (m_bodies.rigidIndex[i] != kNotRigid)
            continue;
        const auto* particle = dynamic_cast<const Particle*>(m_bodies.objects[i].get());
        if (particle && particle->getRadius() > 0.0) {
            m_bodies.rigidIndex[i] = std::uint32_t(m_rigid.system->size());
            m_rigid.system->addPoint(i);
        }
    }
}

void World::givePieces()
{
    rigid::RigidSystem& system = *m_rigid.system;
    if (m_forces.couplings.empty()) // no spring between bodies: no net
        return;
    detail::SpringNeighbours& neighbours = *m_particleSystems.neighbours;
    neighbours.update(m_forces.objects, m_bodies.radii);
    if (neighbours.generation() == m_rigid.piecesGeneration && system.size() == m_rigid.piecesBodies)
        return;
    m_rigid.piecesGeneration = neighbours.generation();
    m_rigid.piecesBodies = system.size();
    std::vector<rigid::Segment> segments;
    for (const auto& [a, b] : neighbours.segments()) {
        const std::uint32_t ka = m_bodies.rigidIndex[a], kb = m_bodies.rigidIndex[b];
        if (ka != kNotRigid && kb != kNotRigid && system.isPoint(ka) && system.isPoint(kb))
            segments.push_back({ka, kb});
    }
    std::vector<std::array<std::uint32_t, 3>> triangles;
    for (const auto& t : neighbours.triangles()) {
        std::array<std::uint32_t, 3> k{};
        bool points = true;
        for (std::size_t e = 0; e < 3; ++e) {
            k[e] = m_bodies.rigidIndex[t[e]];
            points = points && k[e] != kNotRigid && system.isPoint(k[e]);
        }
        if (points)
            triangles.push_back(k);
    }
    system.setPieces(std::move(segments), std::move(triangles));
}

void World::givePointBodies()
{
    rigid::RigidSystem& system = *m_rigid.system;
    for (std::size_t k = 0; k < system.size(); ++k) {
        if (!system.isPoint(k))
            continue;
        const std::size_t i = system.worldIndex(k);
        const auto& p = static_cast<const Particle&>(*m_bodies.objects[i]);
        const State& before = m_bodies.previous[i];
        rigid::RigidSystem::PointBody point;
        point.start = RigidState{before.pos, before.vel, Rotation{}};
        point.end = RigidState{p.getPos(), p.getVel(), Rotation{}};
        point.mass = p.getMass();
        point.radius = p.getRadius();
        point.friction = p.getFriction();
        point.restitution = p.getCor();
        point.integrator = p.getIntegrator();
        point.fixed = p.isFixed();
        point.metInSubsteps = p.getIntegrator() == Integrator::Xpbd; // (integrateXpbd)
        system.setPoint(k, point);
    }
}

void World::storePointBodies()
{
    const rigid::RigidSystem& system = *m_rigid.system;
    for (std::size_t k = 0; k < system.size(); ++k) {
        if (!system.isPoint(k))
            continue;
        const std::size_t i = system.worldIndex(k);
        Body& p = *m_bodies.objects[i];
        if (p.isFixed())
            continue;
        const RigidState& e = system.end(k);
        p.setState(State{e.x, e.v});
        m_bodies.noteIfNotFinite(i, p.getState());
    }
}

void World::integrateRigidFreely(std::span<const std::uint32_t> bodies, double dt)
{
    // One system per integrator, of the awake bodies only: a sleeping pile costs nothing here.
    if (bodies.empty())
        return;
    rigid::RigidSystem& system = *m_rigid.system;
    RigidScratch& r = m_rigid.scratch;
    for (auto& members : r.members)
        members.clear();
    for (const std::uint32_t k : bodies) {
        const std::size_t i = system.worldIndex(k);
        const Integrator integrator = m_bodies.objects[i]->getIntegrator();
        const auto at = std::find(kEveryIntegrator.begin(), kEveryIntegrator.end(), integrator);
        r.members[std::size_t(at - kEveryIntegrator.begin())].push_back(i);
    }
    for (std::size_t m = 0; m < kEveryIntegrator.size(); ++m) {
        const std::vector<std::size_t>& members = r.members[m];
        if (members.empty())
            continue;
        const std::size_t n = members.size();
        r.states.resize(n);
        r.inertia.resize(n);
        r.startAcc.resize(n);
        r.wanted.assign(m_bodies.objects.size(), 0);
        for (const std::size_t i : members)
            r.wanted[i] = 1;
        detail::forEachIndex(n, [&](std::size_t k) {
            const auto& b = static_cast<const RigidBody&>(*m_bodies.objects[members[k]]);
            r.states[k] = system.start(m_bodies.rigidIndex[members[k]]);
            r.inertia[k] = RigidInertia{1.0 / b.getMass(), b.getInertiaBody(), b.getInverseInertiaBody()};
        });
        stepRigid(kEveryIntegrator[m], members, r.wanted, dt);
        pushAtFreeEnd(kEveryIntegrator[m], members, dt);
        detail::forEachIndex(n, [&](std::size_t k) {
            system.setFreeEnd(m_bodies.rigidIndex[members[k]], r.states[k]);
            m_bodies.rigidAcc[members[k]] = r.startAcc[k];
        });
    }
}

void World::pushAtFreeEnd(Integrator integrator, const std::vector<std::size_t>& members, double dt)
{
    // An impulse at the end of the free step changes the end velocity and moves the end pose by
    // the integrator's drift of that change, as the contact solver's impulses do.
    if (m_rigid.endPushes.empty())
        return;
    const double drift = rigid::driftWeight(integrator) * dt;
    RigidScratch& r = m_rigid.scratch;
    // Each body's place among the members, looked up once a push (a sheet may bear many bodies).
    constexpr std::size_t kNotMember = std::numeric_limits<std::size_t>::max();
    r.place.assign(m_bodies.objects.size(), kNotMember);
    for (std::size_t k = 0; k < members.size(); ++k)
        r.place[members[k]] = k;
    for (const auto& push : m_rigid.endPushes) {
        const std::size_t k = r.place[push.body];
        if (k == kNotMember)
            continue;
        RigidState& s = r.states[k];
        const RigidInertia& inertia = r.inertia[k];
        const dvec3 dv = push.impulse * inertia.inverseMass;
        const dvec3 dw = angularVelocity(s.rotation.orientation, inertia.inverseInertiaBody, push.angular);
        s.v += dv;
        s.x += drift * dv;
        s.rotation.momentum += push.angular;
        const dquat& start = m_rigid.system->start(m_bodies.rigidIndex[push.body]).rotation.orientation;
        s.rotation.orientation =
            rigid::turnedByImpulses(start, s.rotation.orientation, drift * dw, rigid::driftWeight(integrator));
    }
}

void World::stepRigid(Integrator integrator, const std::vector<std::size_t>& members,
                      std::span<const std::uint8_t> wanted, double dt)
{
    // As integrateCoupled: the other bodies stay at their start-of-step states and poses while
    // the system's take each stage's.
    RigidScratch& r = m_rigid.scratch;
    const std::size_t n = members.size();
    m_forces.sums.resize(m_bodies.objects.size());
    m_forces.torques.resize(m_bodies.objects.size());
    const BodyStates in{m_bodies.objects, m_bodies.trial, wanted, m_bodies.masses, m_bodies.poses, m_bodies.radii};
    Accumulators out{m_forces.sums, m_forces.torques, &m_forces.scratch};
    bool first = true;
    const auto wrenches = [&](std::span<const RigidState> at, std::span<Wrench> result) {
        detail::forEachIndex(n, [&](std::size_t k) {
            const std::size_t i = members[k];
            m_bodies.trial[i] = State{at[k].x, at[k].v};
            const Rotation& turn = at[k].rotation;
            const dvec3 omega = angularVelocity(turn.orientation, r.inertia[k].inverseInertiaBody, turn.momentum);
            m_bodies.poses[i] = Pose{turn.orientation, omega};
            m_forces.sums[i] = m_forces.torques[i] = dvec3(0.0);
        });
        for (const auto& force : m_forces.objects)
            force->accumulate(in, out);
        detail::forEachIndex(n, [&](std::size_t k) {
            const std::size_t i = members[k];
            result[k] = Wrench{m_forces.sums[i], m_forces.torques[i]};
            if (first) // the first stage is at the start: the bodies' acceleration
                r.startAcc[k] = m_forces.sums[i] * r.inertia[k].inverseMass;
        });
        first = false;
    };
    const auto onCores = [](std::size_t count, const auto& fn) { detail::forEachIndex(count, fn); };
    stepRigidSystem(integrator, std::span<RigidState>(r.states), std::span<const RigidInertia>(r.inertia), dt, wrenches,
                    onCores, &r.buffers);
}

void World::storeRigidBodies()
{
    const rigid::RigidSystem& system = *m_rigid.system;
    // A body that took a restitution impulse bounced (and so did the body it hit).
    for (const rigid::Contact& c : system.contacts()) {
        if (std::none_of(c.points.begin(), c.points.begin() + c.count, [](const auto& p) { return p.bounced; }))
            continue;
        for (const rigid::BodyIndex k : {c.a, c.b})
            if (k < system.size() && !system.isAsleep(k) && !m_bodies.objects[system.worldIndex(k)]->isFixed())
                ++m_bodies.bounces[system.worldIndex(k)];
    }
    // A plain local: a thread_local here would be a different, empty vector on each worker thread.
    std::vector<std::size_t> all(system.size());
    for (std::size_t k = 0; k < system.size(); ++k)
        all[k] = system.worldIndex(k);
    const std::size_t bad = detail::lowestFailing(all, 256, m_bodies.objects.size(), [&](std::size_t k) {
        if (system.isPoint(k))
            return true; // storePointBodies
        const std::size_t i = system.worldIndex(k);
        auto& b = static_cast<RigidBody&>(*m_bodies.objects[i]);
        if (b.isFixed())
            return detail::isFinite(b.getPos()) && detail::isFinite(b.getVel());
        const RigidState& s = system.end(k);
        b.setState(State{s.x, s.v}); // a body that is not finite: the rollback restores it, the message reads it
        if (!detail::isFinite(s.x) || !detail::isFinite(s.v) || !detail::isFinite(s.rotation.momentum) ||
            !isUnit(s.rotation.orientation)) {
            b.setAngularMomentum(s.rotation.momentum); // for the message: its spin, or its orientation
            return false;
        }
        b.setRotation(s.rotation);
        b.setAcc(m_bodies.rigidAcc[i]);
        return true;
    });
    m_bodies.firstNonFinite = std::min(m_bodies.firstNonFinite, bad);
    if (m_surfaces.planes.empty())
        return;
    const std::size_t inside = detail::lowestFailing(all, 1024, m_bodies.objects.size(), [&](std::size_t k) {
        if (system.isPoint(k) || m_bodies.objects[all[k]]->isFixed())
            return true;
        // The bounding radius (a visit to the body's object) only for a centre on or behind a plane.
        const dvec3& x = system.end(k).x;
        const auto reach = [&] { return static_cast<const RigidBody&>(*m_bodies.objects[all[k]]).getBoundingRadius(); };
        for (const Plane& plane : m_surfaces.planes)
            if (plane.distance(x) <= 0.0)
                return detail::surfaceHolding(m_surfaces.planes, x, reach()) < 0;
        return true;
    });
    m_bodies.firstInside = std::min(m_bodies.firstInside, inside);
}

} // namespace pba
