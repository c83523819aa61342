// A World: its bodies, swarms, forces and surfaces, and what can be read of it between steps
// (states, energies, interpolation for drawing). Its step is in world_step.cpp, the coupling of
// its bodies into systems in world_coupling.cpp.
#include "pba/world.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "pba/forces.hpp"

#include "collision_rules.hpp"

namespace pba {

BlowUpError::BlowUpError(std::string body, std::uint64_t step, double time, std::string reason)
    : std::runtime_error(
          fmt::format("{} at step {} (t = {:.15g} s): try a smaller dt or another integrator", reason, step, time)),
      m_body(std::move(body)), m_step(step), m_time(time), m_reason(std::move(reason))
{
}

NonFiniteStateError::NonFiniteStateError(std::string body, std::uint64_t step, double time, std::string quantity)
    : BlowUpError(body, step, time, fmt::format("the {} of body '{}' is not finite", quantity, body)),
      m_quantity(std::move(quantity))
{
}

NonFiniteStateError NonFiniteStateError::inSwarm(const std::string& swarm, std::size_t index, std::uint64_t step,
                                                 double time, std::string quantity)
{
    return NonFiniteStateError(fmt::format("{}[{}]", swarm, index), step, time, std::move(quantity));
}

Body& World::addBody(std::unique_ptr<Body> body)
{
    const auto* rigid = dynamic_cast<const RigidBody*>(body.get());
    m_isRigid.push_back(rigid ? 1 : 0);
    m_previousRotation.push_back(rigid ? rigid->getRotation() : Rotation{});
    m_poses.push_back(rigid ? Pose{rigid->getOrientation(), rigid->getAngularVelocity()} : Pose{});
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
    m_swarms.emplace_back(std::make_unique<Swarm>(desc));
    return *m_swarms.back();
}

SwarmFields World::swarmFields() const
{
    SwarmFields fields;
    for (const auto& force : m_forces)
        force->addToSwarmFields(fields); // each can: addForce and addSwarm refuse the others
    return fields;
}

Force& World::addForce(std::unique_ptr<Force> force)
{
    if (!m_swarms.empty())
        requireActsOnSwarms(*force, m_swarms.front()->name());
    const std::size_t before = m_couplings.size();
    force->appendCouplings(m_couplings);
    m_couplingForce.resize(m_couplings.size(), m_forces.size());
    if (m_couplings.size() != before)
        m_coupling.madeFrom.clear(); // new couplings: make the coupling anew at the next step
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

BodyStates World::currentStates(std::vector<State>& storage, std::vector<Pose>& poses) const
{
    storage.resize(m_bodies.size());
    for (std::size_t i = 0; i < m_bodies.size(); ++i)
        storage[i] = m_bodies[i]->getState();
    poses.clear();
    if (hasRigidBodies()) {
        poses.resize(m_bodies.size());
        for (std::size_t i = 0; i < m_bodies.size(); ++i)
            if (isRigid(i)) {
                const auto& rigid = static_cast<const RigidBody&>(*m_bodies[i]);
                poses[i] = Pose{rigid.getOrientation(), rigid.getAngularVelocity()};
            }
    }
    return BodyStates{m_bodies, storage, {}, {}, poses};
}

dvec3 World::acceleration(std::size_t i, const dvec3& x, const dvec3& v) const
{
    const Body& b = *m_bodies[i];
    if (b.isFixed())
        return dvec3(0.0);
    std::vector<State> states;
    std::vector<Pose> poses;
    BodyStates in = currentStates(states, poses);
    states[i] = State{x, v};
    std::vector<std::uint8_t> wanted(m_bodies.size(), 0);
    wanted[i] = 1;
    in.wanted = wanted;
    std::vector<dvec3> forces(m_bodies.size(), dvec3(0.0));
    Accumulators out{forces, {}};
    for (const auto& force : m_forces)
        force->accumulate(in, out);
    return forces[i] / b.getMass();
}

State World::interpolatedState(std::size_t i, double alpha) const
{
    return interpolate(m_previous[i], m_bodies[i]->getState(), alpha);
}

dquat World::interpolatedOrientation(std::size_t i, double alpha) const
{
    if (!isRigid(i))
        return dquat(1.0, 0.0, 0.0, 0.0);
    const dquat& now = static_cast<const RigidBody&>(*m_bodies[i]).getOrientation();
    return glm::slerp(m_previousRotation[i].orientation, now, alpha);
}

bool World::hasPoints() const
{
    return !m_swarms.empty() || std::any_of(m_isRigid.begin(), m_isRigid.end(), [](std::uint8_t r) { return r == 0; });
}

bool World::hasRigidBodies() const
{
    return std::any_of(m_isRigid.begin(), m_isRigid.end(), [](std::uint8_t r) { return r != 0; });
}

double World::kineticEnergy(std::size_t i) const
{
    const Body& b = *m_bodies[i];
    const double translation = 0.5 * b.getMass() * glm::dot(b.getVel(), b.getVel());
    return isRigid(i) ? translation + static_cast<const RigidBody&>(b).getRotationalKineticEnergy() : translation;
}

double World::potentialEnergy(std::size_t i) const
{
    std::vector<State> states;
    std::vector<Pose> poses;
    const BodyStates in = currentStates(states, poses);
    double e = 0.0;
    for (const auto& force : m_forces)
        e += force->potentialEnergyShare(i, in);
    return e;
}

std::vector<double> World::energies() const
{
    std::vector<State> states;
    std::vector<Pose> poses;
    const BodyStates in = currentStates(states, poses);
    std::vector<double> e(m_bodies.size());
    for (std::size_t i = 0; i < m_bodies.size(); ++i) {
        e[i] = kineticEnergy(i);
        for (const auto& force : m_forces)
            e[i] += force->potentialEnergyShare(i, in);
    }
    return e;
}

double World::totalPotentialEnergy() const
{
    std::vector<State> states;
    std::vector<Pose> poses;
    const BodyStates in = currentStates(states, poses);
    double e = 0.0;
    for (const auto& force : m_forces)
        e += force->totalPotentialEnergy(in);
    return e;
}

double World::totalEnergy() const
{
    double e = totalPotentialEnergy();
    for (std::size_t i = 0; i < m_bodies.size(); ++i)
        e += kineticEnergy(i);
    return e;
}

} // namespace pba
