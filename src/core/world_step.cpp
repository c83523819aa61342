// A World's step: its list of phases, the phases of the bodies alone, the swarms, the checks
// that every state is finite and outside the surfaces, and the clock. The particle systems'
// phases are in world_particle_systems.cpp, the rigid bodies' in world_rigid_bodies.cpp.
#include "pba/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include <fmt/format.h>

#include "surfaces/collision_rules.hpp"
#include "parallel.hpp"
#include "world_checks.hpp"

namespace pba {

namespace {

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
    // Fewer bodies than a block of indices: each loop of the particles' phases is one block, and
    // the other core, woken for them all the same, only slowed a 20 x 20 cloth's step by a third.
    const int particleThreads = m_bodies.objects.size() < detail::kIndexGrain ? 1 : m_threads;
    detail::onCores(particleThreads, [&] {
        m_bodies.storePreviousStates();
        m_swarms.keepForRollback();
        const Coupling& coupling = couple(); // a mixed coupled group throws before anything moves
        openSourceBook();
        integrateIndependent(coupling.independent, dt);
        integrateParticleSystems(coupling, dt);
        collideBalls(dt);
    });
    detail::onCores(m_threads, [&] { stepRigidBodies(dt); });
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
        std::string quantity = detail::isFinite(bad.getPos()) ? "velocity" : "position";
        if (isRigid(m_bodies.firstNonFinite) && detail::isFinite(bad.getPos()) && detail::isFinite(bad.getVel()))
            quantity = detail::isFinite(static_cast<const RigidBody&>(bad).getAngularMomentum()) ? "orientation"
                                                                                               : "angular velocity";
        rollBack();
        throw NonFiniteStateError(bad.getName(), m_clock.steps + 1, m_clock.time + dt, quantity);
    }
    for (const auto& swarm : m_swarms.objects)
        if (const auto& bad = swarm->nonFinite()) {
            const NonFiniteStateError error = NonFiniteStateError::inSwarm(swarm->name(), bad->index, m_clock.steps + 1,
                                                                           m_clock.time + dt, bad->quantity);
            rollBack();
            throw error;
        }
}

void World::checkInsideSurfaces(double dt)
{
    if (m_bodies.firstInside >= m_bodies.objects.size())
        return;
    const auto& bad = static_cast<const RigidBody&>(*m_bodies.objects[m_bodies.firstInside]);
    const int p = detail::surfaceHolding(m_surfaces.planes, bad.getPos(), bad.getBoundingRadius());
    const dvec3 normal = p >= 0 ? m_surfaces.planes[std::size_t(p)].normal : dvec3(0.0, 1.0, 0.0);
    const bool grille = m_surfaces.hole && p == int(m_surfaces.planes.size()) - 1;
    const char* floor = m_surfaces.ground ? "the ground" : "the floor";
    const char* surface = grille ? "the blow dryer's grille" : normal.y > 0.5 ? floor
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
    radii.resize(n);
    frictions.resize(n);
    keys.resize(n);
    trial.resize(n);
    detail::forEachIndex(n, [this](std::size_t i) {
        const Body& b = *objects[i];
        previous[i] = b.getState();
        trial[i] = previous[i]; // the coupled systems' stages start from here
        masses[i] = b.getMass();
        cors[i] = b.getCor();
        const auto* particle = isParticle[i] != 0 ? static_cast<const Particle*>(&b) : nullptr;
        radii[i] = particle ? particle->getRadius() : 0.0;
        frictions[i] = particle ? particle->getFriction() : 0.0;
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

World::ForceOnBody World::forceOn(std::size_t i, const dvec3& x, const dvec3& v) const
{
    const Body& b = *m_bodies.objects[i];
    ForceOnBody f;
    for (const auto& force : m_forces.objects) {
        const dvec3 fk = force->force(i, b, x, v);
        f.total += fk;
        if (force->addsEnergy())
            f.sources += fk;
    }
    return f;
}

namespace {

/// The energy sources' work on a body moving alone, stretch by stretch of its actual free
/// flight (stepWithCollisions' book): each stage of its integrator weighs the sources' force
/// as it weighs the whole force, so the work is their exact share of the kinetic energy
/// m (v1 - v0) . (v0 + v1) / 2 = dt sum_k w_k F_k . (v0 + v1) / 2 that the stretch gave.
/// `source` is the sources' force of the stage the acceleration was last evaluated at.
struct SourceWorkBook {
    const dvec3& source;
    std::span<const double> weights;
    std::size_t stage = 0;
    dvec3 impulse{0.0};
    double work = 0.0;

    template <class Accel>
    auto wrap(Accel& accel)
    {
        stage = 0;
        impulse = dvec3(0.0);
        return [this, &accel](const dvec3& x, const dvec3& v) {
            const dvec3 a = accel(x, v);
            impulse += weights[std::min(stage++, weights.size() - 1)] * source;
            return a;
        };
    }
    void close(double dt, const dvec3& v0, const dvec3& v1) { work += dt * glm::dot(impulse, 0.5 * (v0 + v1)); }
};

} // namespace

void World::openSourceBook()
{
    if (hasEnergySources())
        m_bodies.sourceWork.assign(m_bodies.objects.size(), std::numeric_limits<double>::quiet_NaN());
    else
        m_bodies.sourceWork.clear();
}

void World::integrateIndependent(const std::vector<std::size_t>& bodies, double dt)
{
    const bool book = !m_bodies.sourceWork.empty();
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
        dvec3 source(0.0); // the last evaluation's, for the book
        const double mass = b.getMass();
        auto accel = [this, i, mass, &first, &startAcc, &source](const dvec3& x, const dvec3& v) {
            const ForceOnBody f = forceOn(i, x, v);
            source = f.sources;
            const dvec3 a = f.total / mass;
            if (first) {
                startAcc = a;
                first = false;
            }
            return a;
        };
        State s = b.getState();
        std::array<Plane, kMaxBallPlanes> room;
        const auto planes = ballPlanes(std::span<const Plane>(m_surfaces.planes), m_bodies.radii[i], room);
        int bounces = 0;
        if (book) {
            SourceWorkBook work{source, stageWeights(b.getIntegrator())};
            bounces = stepWithCollisions(m_surfaces.response, b.getIntegrator(), planes, b.getCor(), s.pos, s.vel, dt,
                                         accel, m_bodies.frictions[i], work);
            m_bodies.sourceWork[i] = work.work;
        } else {
            bounces = stepWithCollisions(m_surfaces.response, b.getIntegrator(), planes, b.getCor(), s.pos, s.vel, dt,
                                         accel, m_bodies.frictions[i]);
        }
        m_bodies.bounces[i] += static_cast<std::uint64_t>(bounces);
        b.setState(s);
        b.setAcc(startAcc);
        m_bodies.noteIfNotFinite(i, s);
    }
}

void World::Bodies::noteIfNotFinite(std::size_t i, const State& state)
{
    if (!detail::isFinite(state.pos) || !detail::isFinite(state.vel))
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
    for (std::size_t s = 0; s < m_swarms.objects.size(); ++s) {
        Swarm& swarm = *m_swarms.objects[s];
        std::array<PlaneT<float>, kMaxBallPlanes> room;
        const auto ball = ballPlanes(std::span<const PlaneT<float>>(planes), swarm.radius(), room);
        swarm.step(fields, ball, m_surfaces.response, float(dt), m_threads);
        if (swarm.desc().collide)
            collideGrains(swarm, s, ball, glm::length(dvec3(fields.gravity)) * dt, dt);
    }
}

} // namespace pba
