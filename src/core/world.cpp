// A World: its bodies, swarms, forces and surfaces, and what can be read of it between steps
// (states, energies, interpolation for drawing). Its step is in world_step.cpp, with the phases
// of its particle systems and rigid bodies in world_particle_systems.cpp and
// world_rigid_bodies.cpp, and the coupling of its bodies into systems in world_coupling.cpp.
#include "pba/world.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "pba/forces.hpp"

#include "surfaces/collision_rules.hpp"
#include "rigid/joint_solver.hpp"
#include "rigid/rigid_system.hpp"
#include "swarms/grain_contacts.hpp"
#include "balls/particle_contacts.hpp"
#include "particle_systems/spring_neighbours.hpp"
#include "particle_systems/spring_solvers.hpp"

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

// Out of line: the rigid system and the spring solvers are types of the core's own (src/core/).
World::World()
{
    m_rigid.system = std::make_unique<rigid::RigidSystem>();
    m_particleSystems.springSolvers = std::make_unique<detail::SpringSolvers>();
    m_particleSystems.ballContacts = std::make_unique<detail::BallContacts>();
    m_particleSystems.neighbours = std::make_unique<detail::SpringNeighbours>();
    m_particleSystems.grainContacts = std::make_unique<detail::GrainContacts>();
}
World::World(const World&) = default;
World& World::operator=(const World&) = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

Body& World::addBody(std::unique_ptr<Body> body)
{
    const auto* rigid = dynamic_cast<const RigidBody*>(body.get());
    m_bodies.isRigid.push_back(rigid ? 1 : 0);
    m_bodies.isParticle.push_back(dynamic_cast<const Particle*>(body.get()) ? 1 : 0);
    m_bodies.rigidIndex.push_back(rigid ? std::uint32_t(m_rigid.system->size()) : kNotRigid);
    m_bodies.rigidAcc.push_back(dvec3(0.0));
    if (rigid)
        m_rigid.system->add(m_bodies.objects.size());
    m_bodies.previousRotation.push_back(rigid ? rigid->getRotation() : Rotation{});
    m_bodies.poses.push_back(rigid ? Pose{rigid->getOrientation(), rigid->getAngularVelocity()} : Pose{});
    m_bodies.previous.push_back(body->getState());
    m_bodies.bounces.push_back(0);
    m_bodies.objects.push_back(std::move(body));
    return *m_bodies.objects.back();
}

Particle& World::addParticle(const Particle& particle)
{
    return static_cast<Particle&>(addBody(std::make_unique<Particle>(particle)));
}

namespace {

const Body& jointBodyOf(const std::vector<ClonePtr<Body>>& bodies, std::size_t i, const char* role)
{
    if (i >= bodies.size())
        throw std::invalid_argument(fmt::format("a joint's {} body {} does not exist", role, i));
    return *bodies[i];
}

/// A body's pose as a joint reads it: a particle does not turn.
std::pair<dvec3, dquat> jointPose(const Body& b)
{
    const auto* rigid = dynamic_cast<const RigidBody*>(&b);
    return {b.getPos(), rigid ? rigid->getOrientation() : dquat(1.0, 0.0, 0.0, 0.0)};
}

bool finite(const dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// A unit vector across the unit vector `axis`.
dvec3 across(const dvec3& axis)
{
    const dvec3 other = std::abs(axis.x) < 0.57735 ? dvec3(1.0, 0.0, 0.0) : dvec3(0.0, 1.0, 0.0);
    return glm::normalize(glm::cross(axis, other));
}

/// A particle has no orientation for a hinge or a weld to hold, and two particles (or a particle
/// and the world) are joined by a spring or a pin.
void checkParticleJoint(const JointDesc& desc, const Body& particle, const Body* b, bool bothParticles)
{
    if (desc.type == JointType::Hinge || desc.type == JointType::Fixed)
        throw std::invalid_argument(fmt::format("a {} joint needs two rigid bodies, and '{}' is a particle (join "
                                                "a particle with a ball or distance joint)",
                                                jointTypeName(desc.type), particle.getName()));
    if (!b || bothParticles)
        throw std::invalid_argument(fmt::format("a joint joins a particle to a rigid body, and '{}' is joined to "
                                                "{}",
                                                particle.getName(), b ? "a particle" : "the world"));
}

/// A body's pose at the joint's start, taking world points into its frame (the world's own frame
/// for the world).
struct StartPose {
    dvec3 x{0.0};
    dquat q{1.0, 0.0, 0.0, 0.0};
    dvec3 local(const dvec3& p) const { return glm::conjugate(q) * (p - x); }
};

void setHinge(const JointDesc& desc, const StartPose& a, const StartPose& b, rigid::Joint& j)
{
    const dvec3 axis = unitOrZero(desc.axis);
    if (axis == dvec3(0.0) || !finite(desc.axis))
        throw std::invalid_argument("a hinge's axis must be a non-zero finite vector");
    const dvec3 ref = across(axis);
    j.axisA = a.local(a.x + axis);
    j.axisB = b.local(b.x + axis);
    j.refA = a.local(a.x + ref);
    j.refB = b.local(b.x + ref);
    if (!desc.limits)
        return;
    const auto [lower, upper] = *desc.limits;
    if (!(std::isfinite(lower) && std::isfinite(upper) && lower <= 0.0 && 0.0 <= upper && lower >= -std::numbers::pi &&
          upper <= std::numbers::pi))
        throw std::invalid_argument(fmt::format("a hinge's limits must hold its start angle, 0, within "
                                                "[-pi, pi]: got [{}, {}]", lower, upper));
    j.limited = true;
    j.lower = lower;
    j.upper = upper;
}

void setDistance(const JointDesc& desc, const dvec3& onA, const dvec3& onB, rigid::Joint& j)
{
    j.length = desc.length.value_or(glm::length(onB - onA));
    if (!(j.length >= 0.0 && std::isfinite(j.length)))
        throw std::invalid_argument(fmt::format("a distance joint's length must be finite and >= 0, got {}", j.length));
    if (desc.stiffness && !(*desc.stiffness > 0.0 && std::isfinite(*desc.stiffness)))
        throw std::invalid_argument(fmt::format("a spring's stiffness must be finite and positive, got {}",
                                                *desc.stiffness));
    if (!(desc.damping >= 0.0 && std::isfinite(desc.damping)))
        throw std::invalid_argument(fmt::format("a spring's damping must be finite and >= 0, got {}", desc.damping));
    j.stiffness = desc.stiffness.value_or(0.0);
    j.damping = desc.damping;
    // A rod of no length keeps two points together, as a ball joint does, but along one line:
    // the line between them, which has no direction where it holds. A crate on one under a rope
    // gained 7 times its energy at 1/60 s, where the ball joint's kept it.
    if (j.length == 0.0 && j.stiffness == 0.0)
        j.type = JointType::Ball;
}

} // namespace

std::size_t World::addJoint(const JointDesc& desc)
{
    const Body& a = jointBodyOf(m_bodies.objects, desc.bodyA, "first");
    const Body* b = desc.bodyB ? &jointBodyOf(m_bodies.objects, *desc.bodyB, "second") : nullptr;
    if (b == &a)
        throw std::invalid_argument(fmt::format("a joint joins two bodies, and both are '{}'", a.getName()));
    const bool particleA = !isRigid(desc.bodyA), particleB = b && !isRigid(*desc.bodyB);
    if (particleA || particleB)
        checkParticleJoint(desc, particleA ? a : *b, b, particleA && particleB);
    const dvec3 onA = desc.type == JointType::Distance ? desc.anchors[0] : desc.anchor;
    const dvec3 onB = desc.type == JointType::Distance ? desc.anchors[1] : desc.anchor;
    if (!finite(onA) || !finite(onB))
        throw std::invalid_argument("a joint's anchor must be finite");
    const auto [xa, qa] = jointPose(a);
    const StartPose frameA{xa, qa};
    StartPose frameB;
    if (b)
        std::tie(frameB.x, frameB.q) = jointPose(*b);
    rigid::Joint j;
    j.type = desc.type;
    j.collide = desc.collide;
    j.localA = frameA.local(onA);
    j.localB = frameB.local(onB);
    if (desc.type == JointType::Hinge)
        setHinge(desc, frameA, frameB, j);
    if (desc.type == JointType::Fixed)
        j.rest = glm::conjugate(frameA.q) * frameB.q;
    if (desc.type == JointType::Distance)
        setDistance(desc, onA, onB, j);
    // Checked: the world changes from here on. A particle joined to a body takes part in the
    // rigid system as a point body.
    for (const std::size_t i : {desc.bodyA, desc.bodyB.value_or(desc.bodyA)})
        if (m_bodies.rigidIndex[i] == kNotRigid) {
            m_bodies.rigidIndex[i] = std::uint32_t(m_rigid.system->size());
            m_rigid.system->addPoint(i);
        }
    j.a = m_bodies.rigidIndex[desc.bodyA];
    j.b = b ? m_bodies.rigidIndex[*desc.bodyB] : rigid::kWorldBody;
    m_rigid.system->addJoint(j);
    return m_rigid.system->joints().size() - 1;
}

std::vector<World::ContactPointView> World::contactPoints() const
{
    std::vector<ContactPointView> out;
    contactPoints(out);
    return out;
}

void World::contactPoints(std::vector<ContactPointView>& out) const
{
    const rigid::RigidSystem& system = *m_rigid.system;
    out.clear();
    for (const rigid::Contact& c : system.contacts())
        for (int k = 0; k < c.count; ++k) {
            const rigid::ContactPoint& p = c.points[k];
            if (p.separation > 1e-3 && p.normalImpulse == 0.0)
                continue; // speculative: not touching
            ContactPointView view;
            view.point = p.point;
            view.normal = p.normal;
            view.impulse = p.normalImpulse;
            view.separation = p.separation;
            view.bodyA = system.worldIndex(c.a);
            if (c.b < system.size())
                view.bodyB = system.worldIndex(c.b);
            out.push_back(view);
        }
}

std::size_t World::jointCount() const { return m_rigid.system->joints().size(); }

JointFrame World::jointFrame(std::size_t i) const
{
    const rigid::Joint& j = m_rigid.system->joints()[i];
    auto pose = [&](rigid::BodyIndex k) {
        if (k == rigid::kWorldBody)
            return std::pair{dvec3(0.0), dquat(1.0, 0.0, 0.0, 0.0)};
        return jointPose(*m_bodies.objects[m_rigid.system->worldIndex(k)]);
    };
    const auto [xa, qa] = pose(j.a);
    const auto [xb, qb] = pose(j.b);
    JointFrame frame;
    frame.type = j.type;
    frame.bodyA = m_rigid.system->worldIndex(j.a);
    if (j.b != rigid::kWorldBody)
        frame.bodyB = m_rigid.system->worldIndex(j.b);
    frame.onA = xa + qa * j.localA;
    frame.onB = xb + qb * j.localB;
    if (j.type == JointType::Hinge)
        frame.axis = glm::normalize(qa * j.axisA);
    frame.length = j.length;
    frame.stiffness = j.stiffness;
    frame.damping = j.damping;
    return frame;
}

std::optional<std::size_t> World::findBody(std::string_view name) const
{
    for (std::size_t i = 0; i < m_bodies.objects.size(); ++i)
        if (m_bodies.objects[i]->getName() == name)
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
    if (isSpringSystemMethod(desc.integrator))
        throw std::invalid_argument(fmt::format("swarm '{}' takes {}, a method for particles joined by springs: a "
                                                "swarm has none", desc.name, integratorName(desc.integrator)));
    for (const auto& force : m_forces.objects)
        requireActsOnSwarms(*force, desc.name);
    m_swarms.objects.emplace_back(std::make_unique<Swarm>(desc));
    return *m_swarms.objects.back();
}

SwarmFields World::swarmFields() const
{
    SwarmFields fields;
    for (const auto& force : m_forces.objects)
        force->addToSwarmFields(fields); // each can: addForce and addSwarm refuse the others
    return fields;
}

Force& World::addForce(std::unique_ptr<Force> force)
{
    if (!m_swarms.objects.empty())
        requireActsOnSwarms(*force, m_swarms.objects.front()->name());
    const std::size_t before = m_forces.couplings.size();
    force->appendCouplings(m_forces.couplings);
    m_forces.couplingForce.resize(m_forces.couplings.size(), m_forces.objects.size());
    if (m_forces.couplings.size() != before)
        m_particleSystems.coupling.madeFrom.clear(); // new couplings: make the coupling anew at the next step
    m_forces.objects.push_back(std::move(force));
    return *m_forces.objects.back();
}

void World::setXpbdSubsteps(int substeps)
{
    if (substeps < 1 || substeps > kMaxXpbdSubsteps)
        throw std::invalid_argument(
            fmt::format("xpbd's substeps must be from 1 to {}, got {}", kMaxXpbdSubsteps, substeps));
    m_particleSystems.xpbdSubsteps = substeps;
}

int World::lastImplicitIterations() const
{
    return m_particleSystems.springSolvers->backwardEuler.backwardEuler.iterations();
}

dvec3 World::gravity() const
{
    struct GravitySum final : ForceVisitor {
        dvec3 g{0.0};
        void visit(const Gravity& gravity) override { g += gravity.acceleration(); }
    } sum;
    for (const auto& force : m_forces.objects)
        force->accept(sum);
    return sum.g;
}

void World::setGround(double height)
{
    m_surfaces.room.reset();
    m_surfaces.ground = height;
    m_surfaces.rebuildPlanes();
}

void World::setRoom(const Aabb& room)
{
    m_surfaces.ground.reset();
    m_surfaces.room = room;
    m_surfaces.rebuildPlanes();
}

void World::clearSurfaces()
{
    m_surfaces.ground.reset();
    m_surfaces.room.reset();
    m_surfaces.hole.reset();
    m_surfaces.planes.clear();
}

void World::setFloorHole(const FloorHole& hole)
{
    if (!m_surfaces.ground && !m_surfaces.room)
        throw std::invalid_argument("a floor hole needs a ground or a room");
    if (!(hole.radius > 0.0 && std::isfinite(hole.radius)) || !(hole.depth > 0.0 && std::isfinite(hole.depth)))
        throw std::invalid_argument(fmt::format("a floor hole needs a positive radius and depth, got {} and {}",
                                                hole.radius, hole.depth));
    m_surfaces.hole = hole;
    m_surfaces.rebuildPlanes();
}

void World::Surfaces::rebuildPlanes()
{
    planes.clear();
    if (ground) {
        const auto made = groundPlanes(*ground);
        planes.assign(made.begin(), made.end());
    } else if (room) {
        const auto made = roomPlanes(room->min, room->max);
        planes.assign(made.begin(), made.end());
    }
    if (hole && !planes.empty()) {
        Plane& floor = planes.front(); // both builders put the floor first
        floor.holeRadius = hole->radius;
        floor.holeCentre = dvec3(hole->centre.x, floor.offset, hole->centre.z);
        planes.push_back(Plane{floor.normal, floor.offset - hole->depth}); // the grille
    }
}

BodyStates World::currentStates(std::vector<State>& storage, std::vector<Pose>& poses, bool withStates) const
{
    // Every read-out and the blow-up watch after every step gather the states: a 16,384-member
    // cloth's on all cores.
    storage.resize(withStates ? m_bodies.objects.size() : 0);
    detail::forEachIndex(storage.size(), [&](std::size_t i) { storage[i] = m_bodies.objects[i]->getState(); });
    poses.clear();
    if (hasRigidBodies()) {
        poses.resize(m_bodies.objects.size());
        detail::forEachIndex(poses.size(), [&](std::size_t i) {
            if (isRigid(i)) {
                const auto& rigid = static_cast<const RigidBody&>(*m_bodies.objects[i]);
                poses[i] = Pose{rigid.getOrientation(), rigid.getAngularVelocity()};
            }
        });
    }
    return BodyStates{m_bodies.objects, storage, {}, {}, poses, {}};
}

dvec3 World::acceleration(std::size_t i, const dvec3& x, const dvec3& v) const
{
    const Body& b = *m_bodies.objects[i];
    if (b.isFixed())
        return dvec3(0.0);
    std::vector<State> states;
    std::vector<Pose> poses;
    BodyStates in = currentStates(states, poses);
    states[i] = State{x, v};
    std::vector<std::uint8_t> wanted(m_bodies.objects.size(), 0);
    wanted[i] = 1;
    in.wanted = wanted;
    std::vector<dvec3> forces(m_bodies.objects.size(), dvec3(0.0));
    Accumulators out{forces, {}};
    for (const auto& force : m_forces.objects)
        force->accumulate(in, out);
    return forces[i] / b.getMass();
}

State World::interpolatedState(std::size_t i, double alpha) const
{
    return interpolate(m_bodies.previous[i], m_bodies.objects[i]->getState(), alpha);
}

dquat World::interpolatedOrientation(std::size_t i, double alpha) const
{
    if (!isRigid(i))
        return dquat(1.0, 0.0, 0.0, 0.0);
    const dquat& now = static_cast<const RigidBody&>(*m_bodies.objects[i]).getOrientation();
    return glm::slerp(m_bodies.previousRotation[i].orientation, now, alpha);
}

bool World::hasPoints() const
{
    const auto& flags = m_bodies.isRigid;
    return !m_swarms.objects.empty() || std::any_of(flags.begin(), flags.end(), [](std::uint8_t r) { return r == 0; });
}

bool World::isAsleep(std::size_t i) const
{
    return m_bodies.rigidIndex[i] != kNotRigid && m_rigid.system->isAsleep(m_bodies.rigidIndex[i]);
}

void World::wakeAll() { m_rigid.system->wakeAll(); }

ContactSettings& World::contactSettings() { return m_rigid.system->settings(); }
const ContactSettings& World::contactSettings() const { return m_rigid.system->settings(); }

bool World::hasRigidBodies() const
{
    return std::any_of(m_bodies.isRigid.begin(), m_bodies.isRigid.end(), [](std::uint8_t r) { return r != 0; });
}

double World::kineticEnergy(std::size_t i) const
{
    const Body& b = *m_bodies.objects[i];
    const double translation = 0.5 * b.getMass() * glm::dot(b.getVel(), b.getVel());
    return isRigid(i) ? translation + static_cast<const RigidBody&>(b).getRotationalKineticEnergy() : translation;
}

double World::addSpringJointEnergies(std::span<double> perBody) const
{
    double total = 0.0;
    for (std::size_t i = 0; i < jointCount(); ++i) {
        const rigid::Joint& j = m_rigid.system->joints()[i];
        if (j.type != JointType::Distance || !(j.stiffness > 0.0))
            continue;
        const JointFrame frame = jointFrame(i);
        const double stretch = glm::length(frame.onB - frame.onA) - j.length;
        const double e = 0.5 * j.stiffness * stretch * stretch;
        total += e;
        if (perBody.empty())
            continue;
        perBody[frame.bodyA] += frame.bodyB ? 0.5 * e : e;
        if (frame.bodyB)
            perBody[*frame.bodyB] += 0.5 * e;
    }
    return total;
}

double World::potentialEnergy(std::size_t i) const
{
    std::vector<State> states;
    std::vector<Pose> poses;
    const BodyStates in = currentStates(states, poses);
    double e = 0.0;
    for (const auto& force : m_forces.objects)
        e += force->potentialEnergyShare(i, in);
    if (jointCount() > 0) {
        std::vector<double> joints(m_bodies.objects.size(), 0.0);
        addSpringJointEnergies(joints);
        e += joints[i];
    }
    return e;
}

std::vector<double> World::energies() const
{
    std::vector<State> states;
    std::vector<Pose> poses;
    const BodyStates in = currentStates(states, poses);
    std::vector<double> e(m_bodies.objects.size());
    for (std::size_t i = 0; i < m_bodies.objects.size(); ++i) {
        e[i] = kineticEnergy(i);
        for (const auto& force : m_forces.objects)
            e[i] += force->potentialEnergyShare(i, in);
    }
    addSpringJointEnergies(e);
    return e;
}

double World::totalPotentialEnergy() const
{
    std::vector<State> states;
    std::vector<Pose> poses;
    const BodyStates in = currentStates(states, poses);
    double e = addSpringJointEnergies({});
    for (const auto& force : m_forces.objects)
        e += force->totalPotentialEnergy(in);
    return e;
}

double World::totalEnergy() const
{
    double e = totalPotentialEnergy();
    for (std::size_t i = 0; i < m_bodies.objects.size(); ++i)
        e += kineticEnergy(i);
    return e;
}

bool World::hasEnergySources() const
{
    return std::any_of(m_forces.objects.begin(), m_forces.objects.end(),
                       [](const auto& force) { return force->addsEnergy(); });
}

std::vector<Wrench> World::sourceWrenches(std::span<const State> at) const
{
    const std::size_t n = m_bodies.objects.size();
    std::vector<State> gathered;
    std::vector<Pose> poses;
    const bool given = at.size() == n;
    BodyStates in = currentStates(gathered, poses, !given);
    if (given)
        in.states = at;
    std::vector<dvec3> forces(n, dvec3(0.0)), torques(poses.empty() ? 0 : n, dvec3(0.0));
    Accumulators out{forces, torques};
    for (const auto& force : m_forces.objects)
        if (force->addsEnergy())
            force->accumulate(in, out);
    // (whatever a force gives a fixed body does no work: it does not move)
    std::vector<Wrench> wrenches(n);
    detail::forEachIndex(n, [&](std::size_t i) {
        wrenches[i] = Wrench{forces[i], torques.empty() ? dvec3(0.0) : torques[i]};
    });
    return wrenches;
}

bool World::ballsCollide(std::size_t a, std::size_t b) const
{
    // The radii and the springs' neighbours are the last step's: before a body's first step none.
    if (std::max(a, b) >= m_bodies.radii.size())
        return false;
    return m_bodies.radii[a] > 0.0 && m_bodies.radii[b] > 0.0 && !m_particleSystems.neighbours->near(a, b);
}

} // namespace pba
