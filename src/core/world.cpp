#include "pba/world.hpp"

#include <cmath>

#include <fmt/format.h>

#include "pba/blow_dryer.hpp"
#include "pba/forces.hpp"

#include "collision_rules.hpp"

namespace pba {

NonFiniteStateError::NonFiniteStateError(std::string body, std::uint64_t step, double time, std::string quantity)
    : std::runtime_error(fmt::format("the {} of body '{}' is not finite at step {} (t = {} s): "
                                     "try a smaller dt or another integrator",
                                     quantity, body, step, time)),
      m_body(std::move(body)), m_step(step), m_time(time), m_quantity(std::move(quantity))
{
}

NonFiniteStateError NonFiniteStateError::inSwarm(const std::string& swarm, std::size_t index, std::uint64_t step,
                                                 double time, std::string quantity)
{
    return NonFiniteStateError(fmt::format("{}[{}]", swarm, index), step, time, std::move(quantity));
}

World::World(const World& other)
    : m_swarms(other.m_swarms), m_threads(other.m_threads), m_swarmRollback(other.m_swarmRollback), m_previous(other.m_previous), m_bounces(other.m_bounces), m_ground(other.m_ground), m_room(other.m_room),
      m_hole(other.m_hole),
      m_planes(other.m_planes), m_response(other.m_response), m_time(other.m_time), m_previousTime(other.m_previousTime), m_steps(other.m_steps),
      m_lastDt(other.m_lastDt), m_baseTime(other.m_baseTime), m_baseSteps(other.m_baseSteps)
{
    m_bodies.reserve(other.m_bodies.size());
    for (const auto& body : other.m_bodies)
        m_bodies.push_back(body->clone());
    m_forces.reserve(other.m_forces.size());
    for (const auto& force : other.m_forces)
        m_forces.push_back(force->clone());
}

World& World::operator=(const World& other)
{
    if (this != &other) {
        World copy(other);
        *this = std::move(copy);
    }
    return *this;
}

Body& World::addBody(std::unique_ptr<Body> body)
{
    m_previous.push_back(body->getState());
    m_bounces.push_back(0);
    m_bodies.push_back(std::move(body));
    return *m_bodies.back();
}

Particle& World::addParticle(const Particle& particle)
{
    return static_cast<Particle&>(addBody(std::make_unique<Particle>(particle)));
}

std::optional<std::size_t> World::findBody(std::string_view name) const
{
    for (std::size_t i = 0; i < m_bodies.size(); ++i)
        if (m_bodies[i]->getName() == name)
            return i;
    return std::nullopt;
}

namespace {

/// A force that cannot act on a swarm, in a world with one, would act on the bodies alone and
/// silently leave the swarm out: refused, naming the force's type and the swarm.
void requireActsOnSwarms(const Force& force, const std::string& swarm)
{
    SwarmFields probe;
    if (!force.addToSwarmFields(probe))
        throw std::invalid_argument(
            fmt::format("a {} force cannot act on swarm '{}': a swarm feels gravity, drag and blow dryers only",
                        force.type(), swarm));
}

} // namespace

Swarm& World::addSwarm(const SwarmDesc& desc)
{
    for (const auto& force : m_forces)
        requireActsOnSwarms(*force, desc.name);
    m_swarms.emplace_back(desc);
    return m_swarms.back();
}

SwarmFields World::swarmFields() const
{
    SwarmFields fields;
    for (const auto& force : m_forces)
        force->addToSwarmFields(fields); // each can: addForce and addSwarm refuse the others
    return fields;
}

void World::stepSwarms(double dt)
{
    if (m_swarms.empty())
        return;
    const SwarmFields fields = swarmFields();
    std::vector<PlaneT<float>> planes;
    for (const Plane& p : m_planes)
        planes.push_back({Vec3<float>(p.normal), float(p.offset), float(p.holeRadius), Vec3<float>(p.holeCentre)});
    for (Swarm& swarm : m_swarms)
        swarm.step(fields, planes, m_response, float(dt), m_threads);
}

Force& World::addForce(std::unique_ptr<Force> force)
{
    if (!m_swarms.empty())
        requireActsOnSwarms(*force, m_swarms.front().name());
    m_forces.push_back(std::move(force));
    return *m_forces.back();
}

dvec3 World::gravity() const
{
    struct GravitySum final : ForceVisitor {
        dvec3 g{0.0};
        void visit(const Gravity& gravity) override { g += gravity.acceleration(); }
    } sum;
    for (const auto& force : m_forces)
        force->accept(sum);
    return sum.g;
}

void World::setGround(double height)
{
    m_room.reset();
    m_ground = height;
    rebuildPlanes();
}

void World::setRoom(const Aabb& room)
{
    m_ground.reset();
    m_room = room;
    rebuildPlanes();
}

void World::clearSurfaces()
{
    m_ground.reset();
    m_room.reset();
    m_hole.reset();
    m_planes.clear();
}

void World::setFloorHole(const FloorHole& hole)
{
    if (!m_ground && !m_room)
        throw std::invalid_argument("a floor hole needs a ground or a room");
    if (!(hole.radius > 0.0 && std::isfinite(hole.radius)) || !(hole.depth > 0.0 && std::isfinite(hole.depth)))
        throw std::invalid_argument(fmt::format("a floor hole needs a positive radius and depth, got {} and {}",
                                                hole.radius, hole.depth));
    m_hole = hole;
    rebuildPlanes();
}

void World::rebuildPlanes()
{
    m_planes.clear();
    if (m_ground) {
        const auto planes = groundPlanes(*m_ground);
        m_planes.assign(planes.begin(), planes.end());
    } else if (m_room) {
        const auto planes = roomPlanes(m_room->min, m_room->max);
        m_planes.assign(planes.begin(), planes.end());
    }
    if (m_hole && !m_planes.empty()) {
        Plane& floor = m_planes.front(); // both builders put the floor first
        floor.holeRadius = m_hole->radius;
        floor.holeCentre = dvec3(m_hole->centre.x, floor.offset, m_hole->centre.z);
        m_planes.push_back(Plane{floor.normal, floor.offset - m_hole->depth}); // the grille
    }
}

dvec3 World::acceleration(std::size_t i, const dvec3& x, const dvec3& v) const
{
    const Body& b = *m_bodies[i];
    if (b.isFixed())
        return dvec3(0.0);
    dvec3 f(0.0);
    for (const auto& force : m_forces)
        f += force->force(i, b, x, v);
    return f / b.getMass();
}

State World::interpolatedState(std::size_t i, double alpha) const
{
    return interpolate(m_previous[i], m_bodies[i]->getState(), alpha);
}

double World::kineticEnergy(std::size_t i) const
{
    const Body& b = *m_bodies[i];
    return 0.5 * b.getMass() * glm::dot(b.getVel(), b.getVel());
}

double World::potentialEnergy(std::size_t i) const
{
    const Body& b = *m_bodies[i];
    double e = 0.0;
    for (const auto& force : m_forces)
        e += force->potentialEnergy(i, b, b.getPos());
    return e;
}

void World::step(double dt)
{
    storePreviousStates();
    integrateBodies(dt);
    stepSwarms(dt);
    // The check phase: every body, and every swarm (whose step checked its blocks).
    if (const auto bad = firstNonFinite()) {
        rollBack();
        throw NonFiniteStateError(m_bodies[bad->first]->getName(), m_steps + 1, m_time + dt, bad->second);
    }
    for (const Swarm& swarm : m_swarms)
        if (const auto& bad = swarm.nonFinite()) {
            const NonFiniteStateError error =
                NonFiniteStateError::inSwarm(swarm.name(), bad->index, m_steps + 1, m_time + dt, bad->quantity);
            rollBack();
            throw error;
        }
    // t = t0 + k dt from the last change of dt, rather than a running sum, so the time of
    // step n is n dt to rounding instead of drifting by n rounding errors.
    m_previousTime = m_time;
    if (dt != m_lastDt) {
        m_lastDt = dt;
        m_baseTime = m_time;
        m_baseSteps = m_steps;
    }
    ++m_steps;
    m_time = m_baseTime + static_cast<double>(m_steps - m_baseSteps) * dt;
}

void World::storePreviousStates()
{
    for (std::size_t i = 0; i < m_bodies.size(); ++i)
        m_previous[i] = m_bodies[i]->getState();
    if (m_swarmRollback) {
        m_swarmsBefore.resize(m_swarms.size());
        for (std::size_t s = 0; s < m_swarms.size(); ++s)
            m_swarms[s].saveState(m_swarmsBefore[s]);
    }
}

void World::rollBack()
{
    // So a viewer can pause on the last finite state instead of drawing garbage (previous and
    // current then coincide: nothing moves between them).
    for (std::size_t i = 0; i < m_bodies.size(); ++i)
        m_bodies[i]->setState(m_previous[i]);
    if (m_swarmRollback)
        for (std::size_t s = 0; s < m_swarms.size() && s < m_swarmsBefore.size(); ++s)
            m_swarms[s].restoreState(m_swarmsBefore[s]);
}

void World::integrateBodies(double dt)
{
    for (std::size_t i = 0; i < m_bodies.size(); ++i) {
        Body& b = *m_bodies[i];
        if (b.isFixed())
            continue;
        auto accel = [this, i](const dvec3& x, const dvec3& v) { return acceleration(i, x, v); };
        State s = b.getState();
        const int bounces = stepWithCollisions(m_response, b.getIntegrator(), std::span<const Plane>(m_planes),
                                               b.getCor(), s.pos, s.vel, dt, accel);
        m_bounces[i] += static_cast<std::uint64_t>(bounces);
        b.setState(s);
        b.setAcc(accel(s.pos, s.vel));
    }
}

std::optional<std::pair<std::size_t, std::string>> World::firstNonFinite() const
{
    auto finite = [](const dvec3& u) { return std::isfinite(u.x) && std::isfinite(u.y) && std::isfinite(u.z); };
    for (std::size_t i = 0; i < m_bodies.size(); ++i) {
        if (!finite(m_bodies[i]->getPos()))
            return std::pair{i, std::string("position")};
        if (!finite(m_bodies[i]->getVel()))
            return std::pair{i, std::string("velocity")};
    }
    return std::nullopt;
}

} // namespace pba
