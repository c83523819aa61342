// A World's step: each body alone, each coupled system and each rigid system with its
// integrator, then the swarms, the check that every state is finite, and the clock.
#include "pba/world.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_reduce.h>

#include "pba/vec3_array.hpp"

#include "collision_rules.hpp"
#include "parallel.hpp"
#include "rigid/rigid_system.hpp"
#include "spring_system.hpp"

namespace pba {

namespace {

/// The smallest index of a body, among `members`, for which `check(k)` (which may also store
/// member k's new state) reports false, on all cores in ranges of `grain`; `none` when it
/// reports true for every one. (Each body's work is its own: the answer does not depend on the
/// thread count.)
template <class Check>
std::size_t lowestFailing(const std::vector<std::size_t>& members, std::size_t grain, std::size_t none, Check&& check)
{
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, members.size(), grain), none,
        [&](const tbb::blocked_range<std::size_t>& r, std::size_t lowest) {
            for (std::size_t k = r.begin(); k < r.end(); ++k)
                if (!check(k))
                    lowest = std::min(lowest, members[k]);
            return lowest;
        },
        [](std::size_t a, std::size_t b) { return std::min(a, b); });
}

bool isFinite(const dvec3& u) { return std::isfinite(u.x) && std::isfinite(u.y) && std::isfinite(u.z); }

/// Whether q is the unit quaternion every rigid step ends with. One whose components overflow
/// when squared normalises to zero (a spin of 1e200 rad/s turns it by that much a step) and one
/// that is not finite to NaN: either is a blow-up, not an orientation.
bool isUnit(const dquat& q)
{
    return std::abs(glm::length(q) - 1.0) < 1e-3; // false for NaN
}

/// The first of `planes` that a rigid body's centre x lies on or beyond: at least half the body
/// inside the floor or a wall, since its centre of mass lies within the hull of its points. Not
/// the floor within `reach` (the body's bounding radius) of a hole's edge, where part of a body
/// hangs into the shaft. -1 if none.
int surfaceHolding(std::span<const Plane> planes, const dvec3& x, double reach)
{
    for (std::size_t p = 0; p < planes.size(); ++p) {
        const Plane& plane = planes[p];
        if (!(plane.distance(x) <= 0.0))
            continue;
        if (plane.holeRadius > 0.0 && glm::length(plane.fromHoleAxis(x)) < plane.holeRadius + reach)
            continue;
        return int(p);
    }
    return -1;
}

/// What a body's coupling depends on, in a byte: whether it is fixed, and its integrator.
std::uint8_t couplingKey(const Body& body)
{
    return static_cast<std::uint8_t>((body.isFixed() ? 0x80 : 0) | static_cast<int>(body.getIntegrator()));
}

} // namespace

void World::step(double dt)
{
    if (!(dt > 0.0 && std::isfinite(dt)))
        throw std::invalid_argument(fmt::format("a step's dt must be finite and positive, got {} s", dt));
    m_bodies.firstNonFinite = m_bodies.firstInside = m_bodies.objects.size();
    detail::onCores(m_threads, [&] {
        m_bodies.storePreviousStates();
        m_swarms.keepForRollback();
        const Coupling& coupling = couple(); // a mixed coupled group throws before anything moves
        integrateIndependent(coupling.independent, dt);
        integrateParticleSystems(coupling, dt);
        stepRigidBodies(dt);
    });
    stepSwarms(dt);
    checkFinite(dt);
    checkInsideSurfaces(dt);
    m_clock.advance(dt);
}

void World::checkFinite(double dt)
{
    // Every body (the integration phases checked each as they wrote it), and every swarm
    // (whose step checked its blocks).
    if (m_bodies.firstNonFinite < m_bodies.objects.size()) {
        const Body& bad = *m_bodies.objects[m_bodies.firstNonFinite];
        std::string quantity = isFinite(bad.getPos()) ? "velocity" : "position";
        if (isRigid(m_bodies.firstNonFinite) && isFinite(bad.getPos()) && isFinite(bad.getVel()))
            quantity = isFinite(static_cast<const RigidBody&>(bad).getAngularMomentum()) ? "orientation"
                                                                                       : "angular velocity";
        rollBack();
        throw NonFiniteStateError(bad.getName(), m_clock.steps + 1, m_clock.time + dt, quantity);
    }
    for (const auto& swarm : m_swarms.objects)
        if (const auto& bad = swarm->nonFinite()) {
            const NonFiniteStateError error =
                NonFiniteStateError::inSwarm(swarm->name(), bad->index, m_clock.steps + 1, m_clock.time + dt, bad->quantity);
            rollBack();
            throw error;
        }
}

void World::checkInsideSurfaces(double dt)
{
    if (m_bodies.firstInside >= m_bodies.objects.size())
        return;
    const auto& bad = static_cast<const RigidBody&>(*m_bodies.objects[m_bodies.firstInside]);
    const int p = surfaceHolding(m_surfaces.planes, bad.getPos(), bad.getBoundingRadius());
    const dvec3 normal = p >= 0 ? m_surfaces.planes[std::size_t(p)].normal : dvec3(0.0, 1.0, 0.0);
    const bool grille = m_surfaces.hole && p == int(m_surfaces.planes.size()) - 1;
    const char* surface = grille ? "the blow dryer's grille" : normal.y > 0.5 ? (m_surfaces.ground ? "the ground" : "the floor")
                          : normal.y < -0.5                               ? "the ceiling"
                                                                          : "a wall";
    BlowUpError error(bad.getName(), m_clock.steps + 1, m_clock.time + dt,
                      fmt::format("the centre of mass of body '{}' is inside {}", bad.getName(), surface));
    rollBack();
    throw error;
}

void World::StepClock::advance(double dt)
{
    // t = t0 + k dt from the last change of dt, rather than a running sum, so the time of
    // step n is n dt to rounding instead of drifting by n rounding errors.
    previousTime = time;
    if (dt != lastDt) {
        lastDt = dt;
        baseTime = time;
        baseSteps = steps;
    }
    ++steps;
    time = baseTime + static_cast<double>(steps - baseSteps) * dt;
}

void World::Bodies::storePreviousStates()
{
    // One visit to each body's object for all the step reads of it: a 128 x 128 cloth's 16,384
    // heap objects are slow memory, and each further pass over them cost as much as its springs.
    const std::size_t n = objects.size();
    masses.resize(n);
    cors.resize(n);
    keys.resize(n);
    trial.resize(n);
    detail::forEachIndex(n, [this](std::size_t i) {
        const Body& b = *objects[i];
        previous[i] = b.getState();
        trial[i] = previous[i]; // the coupled systems' stages start from here
        masses[i] = b.getMass();
        cors[i] = b.getCor();
        keys[i] = couplingKey(b);
        if (isRigid[i] != 0) {
            const auto& rigid = static_cast<const RigidBody&>(b);
            previousRotation[i] = rigid.getRotation();
            if (b.isFixed()) // a moving one's pose is set at each stage of its system's step
                poses[i] = Pose{rigid.getOrientation(), rigid.getAngularVelocity()};
        }
    });
}

void World::Swarms::keepForRollback()
{
    if (!rollback)
        return;
    before.resize(objects.size());
    for (std::size_t s = 0; s < objects.size(); ++s)
        objects[s]->saveState(before[s]);
}

void World::rollBack()
{
    // So a viewer can pause on the last finite state instead of drawing garbage (previous and
    // current then coincide: nothing moves between them).
    m_bodies.rollBack();
    m_swarms.rollBack();
}

void World::Bodies::rollBack()
{
    for (std::size_t i = 0; i < objects.size(); ++i) {
        objects[i]->setState(previous[i]);
        if (isRigid[i] != 0)
            static_cast<RigidBody&>(*objects[i]).setRotation(previousRotation[i]);
    }
}

void World::Swarms::rollBack()
{
    if (rollback)
        for (std::size_t s = 0; s < objects.size() && s < before.size(); ++s)
            objects[s]->restoreState(before[s]);
}

dvec3 World::aloneAcceleration(std::size_t i, const dvec3& x, const dvec3& v) const
{
    const Body& b = *m_bodies.objects[i];
    dvec3 f(0.0);
    for (const auto& force : m_forces.objects)
        f += force->force(i, b, x, v);
    return f / b.getMass();
}

void World::integrateIndependent(const std::vector<std::size_t>& bodies, double dt)
{
    for (const std::size_t i : bodies) {
        Body& b = *m_bodies.objects[i];
        if (b.isFixed()) {
            m_bodies.noteIfNotFinite(i, b.getState()); // a program may have put it anywhere
            continue;
        }
        // Every integrator's first evaluation is at the start state: that one is kept as the
        // body's acceleration, rather than evaluating all the forces once more after the step.
        bool first = true;
        dvec3 startAcc(0.0);
        auto accel = [this, i, &first, &startAcc](const dvec3& x, const dvec3& v) {
            const dvec3 a = aloneAcceleration(i, x, v);
            if (first) {
                startAcc = a;
                first = false;
            }
            return a;
        };
        State s = b.getState();
        const int bounces = stepWithCollisions(m_surfaces.response, b.getIntegrator(), std::span<const Plane>(m_surfaces.planes),
                                               b.getCor(), s.pos, s.vel, dt, accel);
        m_bodies.bounces[i] += static_cast<std::uint64_t>(bounces);
        b.setState(s);
        b.setAcc(startAcc);
        m_bodies.noteIfNotFinite(i, s);
    }
}

void World::integrateParticleSystems(const Coupling& coupling, double dt)
{
    for (std::size_t k = 0; k < kParticleIntegrators.size(); ++k) {
        const Integrator integrator = kParticleIntegrators[k];
        const auto& members = coupling.systems[k];
        if (members.empty())
            continue;
        if (integrator == Integrator::ImplicitEuler)
            integrateBackwardEuler(members, coupling.wanted[k], dt);
        else if (integrator == Integrator::Xpbd)
            integrateXpbd(members, coupling.wanted[k], dt);
        else
            integrateCoupled(integrator, members, coupling.wanted[k], dt);
    }
}

void World::startSystem(const std::vector<std::size_t>& members)
{
    const std::size_t n = members.size();
    CoupledScratch& s = m_particleSystems.scratch;
    s.x.resize(n);
    s.v.resize(n);
    s.acc.resize(n);
    detail::forEachIndex(n, [&](std::size_t k) {
        s.x[k] = m_bodies.previous[members[k]].pos;
        s.v[k] = m_bodies.previous[members[k]].vel;
    });
}

void World::sumSystemForces(const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted,
                            std::span<const dvec3> x, std::span<const dvec3> v, const detail::SpringSystem* constraints)
{
    // Every body of the world sits at its start-of-step state (storePreviousStates put it in
    // m_bodies.trial) except the system's, which take each stage's trial state. (A system integrated
    // before this one leaves its bodies at its last stage: no force couples two systems.)
    m_forces.sums.resize(m_bodies.objects.size());
    detail::forEachIndex(members.size(), [&](std::size_t k) {
        if (!x.empty())
            m_bodies.trial[members[k]] = State{x[k], v[k]};
        m_forces.sums[members[k]] = dvec3(0.0);
    });
    const BodyStates in{m_bodies.objects, m_bodies.trial, wanted, m_bodies.masses, {}};
    Accumulators out{m_forces.sums, {}, &m_forces.scratch};
    for (std::size_t f = 0; f < m_forces.objects.size(); ++f)
        if (!constraints || !constraints->isSpring(f))
            m_forces.objects[f]->accumulate(in, out);
}

void World::integrateCoupled(Integrator integrator, const std::vector<std::size_t>& members,
                             std::span<const std::uint8_t> wanted, double dt)
{
    const std::size_t n = members.size();
    CoupledScratch& s = m_particleSystems.scratch;
    startSystem(members);
    bool first = true;
    auto accel = [&](const Vec3Array& xs, const Vec3Array& vs) {
        sumSystemForces(members, wanted, std::span<const dvec3>(xs.begin(), n), std::span<const dvec3>(vs.begin(), n),
                        nullptr);
        Vec3Array a(n);
        // The first stage is at the start state: the bodies' acceleration, kept in s.acc.
        detail::forEachIndex(n, [&](std::size_t k) {
            a[k] = m_forces.sums[members[k]] / m_bodies.masses[members[k]];
            if (first)
                s.acc[k] = a[k];
        });
        first = false;
        return a;
    };
    integrate(integrator, s.x, s.v, dt, accel);
    collideAndStore(members);
}

void World::collideAndStore(const std::vector<std::size_t>& members)
{
    // Collisions, the bodies' new states and the check that they are finite in one pass, so
    // each body's object is visited once here: a cloth's bodies are many and far apart.
    const std::span<const Plane> planes(m_surfaces.planes);
    const CoupledScratch& s = m_particleSystems.scratch;
    const std::size_t bad = lowestFailing(members, 2048, m_bodies.objects.size(), [&](std::size_t k) {
        const std::size_t i = members[k];
        State end{s.x[k], s.v[k]};
        if (!planes.empty())
            m_bodies.bounces[i] += static_cast<std::uint64_t>(
                coupledCollisionResponse() == CollisionResponse::Clamp
                    ? clampAfterStep(planes, m_bodies.cors[i], m_bodies.previous[i].pos, end.pos, end.vel)
                    : reflectAfterStep(planes, m_bodies.cors[i], m_bodies.previous[i].pos, end.pos, end.vel));
        Body& b = *m_bodies.objects[i];
        b.setState(end);
        b.setAcc(s.acc[k]);
        return isFinite(end.pos) && isFinite(end.vel);
    });
    m_bodies.firstNonFinite = std::min(m_bodies.firstNonFinite, bad);
}

void World::stepRigidBodies(double dt)
{
    rigid::RigidSystem& system = *m_rigid.system;
    if (system.size() == 0)
        return;
    thread_local std::vector<const RigidBody*> bodies;
    bodies.resize(system.size());
    for (std::size_t k = 0; k < system.size(); ++k)
        bodies[k] = static_cast<const RigidBody*>(m_bodies.objects[system.worldIndex(k)].get());
    system.begin(bodies);
    integrateRigidFreely(system.awake(), dt);
    system.findContacts(m_surfaces.planes, dt);
    integrateRigidFreely(system.woken(), dt); // touched by an awake body: they move this step too
    system.solve(gravity(), dt);
    storeRigidBodies();
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
        const auto at = std::find(kEveryIntegrator.begin(), kEveryIntegrator.end(), m_bodies.objects[i]->getIntegrator());
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
        detail::forEachIndex(n, [&](std::size_t k) {
            system.setFreeEnd(m_bodies.rigidIndex[members[k]], r.states[k]);
            m_bodies.rigidAcc[members[k]] = r.startAcc[k];
        });
    }
}

void World::stepRigid(Integrator integrator, const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted,
                      double dt)
{
    // As integrateCoupled: the other bodies stay at their start-of-step states and poses while
    // the system's take each stage's.
    RigidScratch& r = m_rigid.scratch;
    const std::size_t n = members.size();
    m_forces.sums.resize(m_bodies.objects.size());
    m_forces.torques.resize(m_bodies.objects.size());
    const BodyStates in{m_bodies.objects, m_bodies.trial, wanted, m_bodies.masses, m_bodies.poses};
    Accumulators out{m_forces.sums, m_forces.torques, &m_forces.scratch};
    bool first = true;
    const auto wrenches = [&](std::span<const RigidState> at, std::span<Wrench> result) {
        detail::forEachIndex(n, [&](std::size_t k) {
            const std::size_t i = members[k];
            m_bodies.trial[i] = State{at[k].x, at[k].v};
            const Rotation& turn = at[k].rotation;
            m_bodies.poses[i] = Pose{turn.orientation, angularVelocity(turn.orientation, r.inertia[k].inverseInertiaBody, turn.momentum)};
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
    const std::size_t bad = lowestFailing(all, 256, m_bodies.objects.size(), [&](std::size_t k) {
        const std::size_t i = system.worldIndex(k);
        auto& b = static_cast<RigidBody&>(*m_bodies.objects[i]);
        if (b.isFixed())
            return isFinite(b.getPos()) && isFinite(b.getVel());
        const RigidState& s = system.end(k);
        b.setState(State{s.x, s.v}); // a body that is not finite: the rollback restores it, the message reads it
        if (!isFinite(s.x) || !isFinite(s.v) || !isFinite(s.rotation.momentum) || !isUnit(s.rotation.orientation)) {
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
    const std::size_t inside = lowestFailing(all, 1024, m_bodies.objects.size(), [&](std::size_t k) {
        if (m_bodies.objects[all[k]]->isFixed())
            return true;
        // The bounding radius (a visit to the body's object) only for a centre on or behind a plane.
        const dvec3& x = system.end(k).x;
        const auto reach = [&] { return static_cast<const RigidBody&>(*m_bodies.objects[all[k]]).getBoundingRadius(); };
        for (const Plane& plane : m_surfaces.planes)
            if (plane.distance(x) <= 0.0)
                return surfaceHolding(m_surfaces.planes, x, reach()) < 0;
        return true;
    });
    m_bodies.firstInside = std::min(m_bodies.firstInside, inside);
}

void World::Bodies::noteIfNotFinite(std::size_t i, const State& state)
{
    if (!isFinite(state.pos) || !isFinite(state.vel))
        firstNonFinite = std::min(firstNonFinite, i);
}

void World::stepSwarms(double dt)
{
    if (m_swarms.objects.empty())
        return;
    const SwarmFields fields = swarmFields();
    std::vector<PlaneT<float>> planes;
    for (const Plane& p : m_surfaces.planes)
        planes.push_back({Vec3<float>(p.normal), float(p.offset), float(p.holeRadius), Vec3<float>(p.holeCentre)});
    for (const auto& swarm : m_swarms.objects)
        swarm->step(fields, planes, m_surfaces.response, float(dt), m_threads);
}

} // namespace pba
