#include "rigid/rigid_system.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include "material_rule.hpp"
#include "parallel.hpp"
#include "rigid/carried_manifold.hpp"
#include "rigid/room_contacts.hpp"

namespace pba::rigid {

namespace {

using contact::CollisionShape;
using contact::Transform;

/// Bodies a task in the per-body loops: a body's own work is a few hundred nanoseconds, and
/// waking the other core for a few hundred of them costs more than it saves.
constexpr std::size_t kBodyGrain = 256;

/// The box around a shape at a pose: a polyhedron's few vertices exactly, a sphere's or a
/// many-vertexed hull's bounding sphere.
Box boundsOf(const CollisionShape& shape, const dvec3& x, const dquat& q)
{
    if (shape.kind == CollisionShape::Kind::Polyhedron && shape.polyhedron->vertices.size() <= 16) {
        const dmat3 r = glm::mat3_cast(q);
        Box box{dvec3(INFINITY), dvec3(-INFINITY)};
        for (const dvec3& v : shape.polyhedron->vertices) {
            const dvec3 p = x + r * v;
            box.min = glm::min(box.min, p);
            box.max = glm::max(box.max, p);
        }
        return box;
    }
    const double r = shape.boundingRadius();
    return {x - r, x + r};
}

Box merged(const Box& a, const Box& b) { return {glm::min(a.min, b.min), glm::max(a.max, b.max)}; }

dvec3 worldAngularVelocity(const RigidState& s, const dmat3& inverseInertiaBody)
{
    return angularVelocity(s.rotation.orientation, inverseInertiaBody, s.rotation.momentum);
}

/// 1/2 m v.v + 1/2 omega.L - m g.x: what no contact may add to.
double energyInGravity(const RigidState& s, double inverseMass, const dmat3& inverseInertiaBody, const dvec3& g)
{
    const double mass = 1.0 / inverseMass;
    const dvec3 omega = worldAngularVelocity(s, inverseInertiaBody);
    return 0.5 * mass * glm::dot(s.v, s.v) + 0.5 * glm::dot(omega, s.rotation.momentum) - mass * glm::dot(g, s.x);
}

double sphereRadius(const CollisionShape& shape)
{
    return shape.kind == CollisionShape::Kind::Sphere ? shape.radius : 0.0;
}

} // namespace

void RigidSystem::add(std::size_t worldIndex)
{
    // The world's static body and the room's surfaces are numbered after the bodies: the
    // contacts that name them are numbered anew.
    m_cache.clear();
    m_world.push_back(worldIndex);
    m_material.emplace_back();
    m_motion.push_back(Motion::Awake);
    m_isPoint.push_back(0);
    m_stillFor.push_back(0.0);
    m_sleepingIsland.push_back(Islands::npos);
    m_start.emplace_back();
    m_end.emplace_back();
}

void RigidSystem::addPoint(std::size_t worldIndex)
{
    add(worldIndex);
    m_isPoint.back() = 1;
    // A joint may join it before its first step: a point until setPoint says more.
    m_material.back().shape = std::make_shared<const CollisionShape>();
}

void RigidSystem::begin(std::span<const RigidBody* const> bodies)
{
    const std::size_t n = m_world.size();
    m_awake.clear();
    m_woken.clear();
    m_points.clear();
    for (std::size_t k = 0; k < n; ++k) {
        if (m_isPoint[k])
            continue;
        const RigidBody& b = *bodies[k];
        Material& m = m_material[k];
        if (m.shape && m.shape != b.getCollisionShape())
            m_cache.clear(); // a body given a new shape: no contact of its old one is carried over
        m.shape = b.getCollisionShape();
        m.friction = b.getFriction();
        m.restitution = b.getCor();
        m.inverseMass = b.isFixed() ? 0.0 : 1.0 / b.getMass();
        m.inverseInertiaBody = b.isFixed() ? dmat3(0.0) : b.getInverseInertiaBody();
        m.driftWeight = driftWeight(b.getIntegrator());
        m_start[k] = RigidState{b.getPos(), b.getVel(), b.getRotation()};
        m_end[k] = m_start[k];
        if (b.isFixed())
            m_motion[k] = Motion::Static;
        else if (m_motion[k] == Motion::Static) // a body a program has just let go of
            m_motion[k] = Motion::Awake;
        if (m_motion[k] == Motion::Awake)
            m_awake.push_back(std::uint32_t(k));
    }
}

void RigidSystem::setPoint(std::size_t k, const PointBody& p)
{
    Material& m = m_material[k];
    if (!m.shape || m.shape->radius != p.radius) {
        auto ball = std::make_shared<CollisionShape>();
        ball->radius = p.radius;
        m.shape = std::move(ball);
    }
    m.friction = p.friction;
    m.restitution = p.restitution;
    m.inverseMass = p.fixed ? 0.0 : 1.0 / p.mass;
    m.inverseInertiaBody = dmat3(0.0); // a point does not turn
    m.driftWeight = driftWeight(p.integrator);
    m.metInSubsteps = p.metInSubsteps;
    m.springJointsInItsSolve = isSpringSystemMethod(p.integrator);
    m_start[k] = p.start;
    m_end[k] = p.end;
    m_stillFor[k] = 0.0; // its island never sleeps: the particle moves on under its own forces
    m_motion[k] = p.fixed ? Motion::Static : Motion::Awake;
    if (!p.fixed)
        m_points.push_back(std::uint32_t(k));
}

bool RigidSystem::joinedApart(BodyIndex a, BodyIndex b) const
{
    const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
    return !m_joinedApart.empty() && std::binary_search(m_joinedApart.begin(), m_joinedApart.end(), key);
}

void RigidSystem::addJoint(const Joint& joint)
{
    m_joints.push_back(joint);
    // Joined bodies meet at the joint (a hinge's links, a rope's end on a crate's surface): a
    // contact there would push them off what holds them.
    if (joint.b != kWorldBody && !joint.collide) {
        const std::uint64_t key = (std::uint64_t(std::min(joint.a, joint.b)) << 32) | std::max(joint.a, joint.b);
        m_joinedApart.insert(std::upper_bound(m_joinedApart.begin(), m_joinedApart.end(), key), key);
    }
}

void RigidSystem::boundingBoxes(double dt)
{
    const std::size_t n = m_world.size();
    m_reach.assign(n, 0.0);
    m_spinReach.assign(n, 0.0);
    m_boxes.resize(n);
    detail::forEachIndex(n, [&](std::size_t k) {
        const CollisionShape& shape = *m_material[k].shape;
        const RigidState& s = m_start[k];
        const RigidState& e = m_end[k];
        Box box = boundsOf(shape, s.x, s.rotation.orientation);
        if (m_motion[k] == Motion::Awake) {
            // No point of the body moves further in the step than its centre and its spin's arc,
            // nor by its spin further than across its bounding sphere.
            const dmat3& iBody = m_material[k].inverseInertiaBody;
            const double spin = std::max(glm::length(worldAngularVelocity(s, iBody)),
                                         glm::length(worldAngularVelocity(e, iBody)));
            m_spinReach[k] = std::min(spin * dt, 2.0) * shape.boundingRadius();
            m_reach[k] = glm::length(e.x - s.x) + m_spinReach[k];
            box = merged(box, boundsOf(shape, e.x, e.rotation.orientation));
        }
        const double pad = 0.5 * m_settings.contactMargin;
        m_boxes[k] = {box.min - pad, box.max + pad};
    }, kBodyGrain);
}

void RigidSystem::widenForPushes()
{
    // A body struck within the step by a partner moves further than its own free motion: up to
    // as far as the partner comes towards it. Its contacts with everything else must reach that
    // far too, or a die knocked down by one landing on it is driven into the die under it with
    // no contact between them to stop it (an overlap of a centimetre or more at a heap's landing).
    const std::size_t n = m_world.size();
    m_push.assign(n, Push{});
    const auto ownMotion = [&](std::uint32_t k) { return m_end[k].x - m_start[k].x; };
    const auto pushed = [&](std::uint32_t k, const dvec3& by) {
        Push& push = m_push[k];
        push.length = std::max(push.length, glm::length(by));
        push.low = glm::max(push.low, -by);
        push.high = glm::max(push.high, by);
    };
    for (const BodyPair& p : m_pairs) {
        if (m_motion[p.a] != Motion::Awake || m_motion[p.b] != Motion::Awake)
            continue;
        // How far their centres come towards each other in the free step (a pair falling side by
        // side strikes nothing), and so may push each other on, along the line between them.
        const dvec3 apart = m_start[p.b].x - m_start[p.a].x;
        const double distance = glm::length(apart);
        if (!(distance > 0.0))
            continue;
        const dvec3 u = apart / distance;
        const double closing = -glm::dot(ownMotion(p.b) - ownMotion(p.a), u);
        if (!(closing > 0.0))
            continue;
        pushed(p.a, -closing * u);
        pushed(p.b, closing * u);
    }
    // What the contact margin already covers is no news: only a harder blow widens a body's reach.
    const std::size_t found = m_pairs.size();
    for (std::uint32_t k = 0; k < n; ++k) {
        const Push& push = m_push[k];
        if (!(push.length > m_settings.contactMargin) || m_isPoint[k])
            continue;
        m_reach[k] += push.length;
        const Box& b = m_boxes[k];
        m_broadPhase.partnersOf(k, {b.min - push.low, b.max + push.high}, m_boxes, m_isPoint, m_pairs);
    }
    if (m_pairs.size() == found)
        return;
    std::sort(m_pairs.begin(), m_pairs.end());
    m_pairs.erase(std::unique(m_pairs.begin(), m_pairs.end()), m_pairs.end());
}

void RigidSystem::collidePairs()
{
    // Written in place, in the pairs' order: the cache's list starts with them.
    auto& out = m_cache.contacts();
    // Room for the room's contacts too: growing the list under them would copy every pair's.
    out.reserve(m_pairs.size() + 2 * m_awake.size());
    out.clear();
    out.resize(m_pairs.size()); // every contact a new one
    tbb::parallel_for(std::size_t(0), m_pairs.size(), [&](std::size_t p) {
        const BodyPair pair = m_pairs[p];
        Contact& c = out[p];
        c.a = pair.a;
        c.b = pair.b;
        if (joinedApart(pair.a, pair.b) || m_material[pair.a].metInSubsteps || m_material[pair.b].metInSubsteps)
            return; // no points
        const Contact* old = m_cache.previous(c.key());
        if (old)
            c.sat = old->sat;
        const RigidState& a = m_start[pair.a];
        const RigidState& b = m_start[pair.b];
        const dquat& qa = a.rotation.orientation;
        const dquat& qb = b.rotation.orientation;
        const Transform ta{a.x, glm::mat3_cast(qa)};
        const Transform tb{b.x, glm::mat3_cast(qb)};
        const double margin = m_reach[pair.a] + m_reach[pair.b] + m_settings.contactMargin;
        const CollisionShape& shapeB = *m_material[pair.b].shape;
        if (!old || !carryManifold(*old, ta, qa, tb, qb, shapeB.boundingRadius(), margin, c)) {
            const CollisionShape& shapeA = *m_material[pair.a].shape;
            const contact::Manifold m = contact::collide(shapeA, ta, shapeB, tb, margin, &c.sat);
            c.takePoints(m);
            if (m.count > 0 && shapeA.kind == CollisionShape::Kind::Polyhedron &&
                shapeB.kind == CollisionShape::Kind::Polyhedron)
                c.found = pairPose(ta, qa, b.x, qb, m.normal, margin);
        }
        c.radiusA = sphereRadius(*m_material[pair.a].shape);
        c.radiusB = sphereRadius(*m_material[pair.b].shape);
        c.friction = detail::combinedFriction(m_material[pair.a].friction, m_material[pair.b].friction);
        c.restitution = detail::combinedRestitution(m_material[pair.a].restitution, m_material[pair.b].restitution);
        m_cache.warmStart(c, old);
    });
    // Pairs whose boxes overlap but whose shapes do not touch stay, with no points: they keep
    // their separating axis for the next step.
}

void RigidSystem::collideRoom(std::span<const Plane> planes)
{
    const std::size_t n = m_world.size();
    constexpr std::size_t kChunk = 256;
    m_roomChunks.resize((n + kChunk - 1) / kChunk);
    tbb::parallel_for(std::size_t(0), m_roomChunks.size(), [&](std::size_t chunk) {
        auto& out = m_roomChunks[chunk];
        out.clear();
        for (std::size_t k = chunk * kChunk; k < std::min(n, (chunk + 1) * kChunk); ++k) {
            if (m_motion[k] != Motion::Awake || m_isPoint[k])
                continue; // a particle meets the room with its own rule
            const RigidState& s = m_start[k];
            const std::size_t first = out.size();
            // Its spin turns the body within its bounding sphere: a sphere that stays clear of a
            // wall needs no contact with it, however fast the body spins (a box spun at 2,000
            // rad/s beside a floor it never comes near was kicked by the floor's speculative
            // contact, whose approach is linear in the spin).
            const double margin = m_reach[k] + m_settings.contactMargin;
            collideWithRoom(*m_material[k].shape, Transform{s.x, glm::mat3_cast(s.rotation.orientation)}, planes,
                            margin, BodyIndex(k), BodyIndex(n + 1), out, margin - m_spinReach[k]);
            for (std::size_t c = first; c < out.size(); ++c) {
                // The room keeps each body's own friction and restitution.
                out[c].friction = m_material[k].friction;
                out[c].radiusA = sphereRadius(*m_material[k].shape);
                out[c].restitution = m_material[k].restitution;
                m_cache.warmStart(out[c]);
            }
        }
    });
    auto& out = m_cache.contacts();
    for (const auto& chunk : m_roomChunks)
        out.insert(out.end(), chunk.begin(), chunk.end());
}

void RigidSystem::carrySleepingContacts()
{
    // A sleeping body's contacts with other sleeping or static bodies are not looked for again:
    // they stay as they were, impulses and all, for the step that wakes it.
    const std::size_t n = m_world.size();
    auto awake = [&](BodyIndex i) { return i < n && m_motion[i] == Motion::Awake; };
    for (const Contact& c : m_cache.previousContacts())
        if (!awake(c.a) && !awake(c.b) && c.count > 0)
            m_cache.contacts().push_back(c);
}

void RigidSystem::wakeIsland(std::uint32_t body)
{
    const std::uint32_t island = m_sleepingIsland[body];
    if (island == Islands::npos)
        return;
    for (const std::uint32_t k : m_sleepingIslands[island]) {
        m_motion[k] = Motion::Awake;
        m_stillFor[k] = 0.0;
        m_sleepingIsland[k] = Islands::npos;
        m_woken.push_back(k);
    }
    m_sleepingIslands[island].clear();
}

void RigidSystem::wakeTouched()
{
    const std::size_t n = m_world.size();
    for (const Contact& c : m_cache.contacts()) {
        if (c.count == 0 || c.b >= n)
            continue;
        const Motion a = m_motion[c.a], b = m_motion[c.b];
        if (a == Motion::Awake && b == Motion::Asleep)
            wakeIsland(c.b);
        else if (b == Motion::Awake && a == Motion::Asleep)
            wakeIsland(c.a);
    }
    std::sort(m_woken.begin(), m_woken.end());
}

void RigidSystem::findContacts(std::span<const Plane> planes, double dt)
{
    if (planes.size() * 2 != m_surfaces) {
        m_surfaces = planes.size() * 2;
        m_cache.clear(); // the room's surfaces are numbered anew
    }
    m_planes.assign(planes.begin(), planes.end());
    // Nothing awake: every contact is a sleeping one, as the cache holds it (a settled pile costs
    // a look at each body, no more).
    if (!anythingAwake())
        return;
    m_cache.beginStep();
    boundingBoxes(dt);
    m_broadPhase.findPairs(m_boxes, m_motion, m_isPoint, m_pairs);
    widenForPushes();
    collidePairs();
    collideRoom(planes);
    carrySleepingContacts();
    wakeTouched();
}

void RigidSystem::prepareBodies(double dt, std::size_t surfaces)
{
    const std::size_t n = m_world.size();
    m_solverBodies.assign(n + 1 + surfaces, SolverBody{}); // the bodies, the world, the room
    m_energyStart.resize(n);
    m_energyFree.resize(n);
    (void)dt;
    detail::forEachIndex(n, [&](std::size_t k) {
        SolverBody& b = m_solverBodies[k];
        const RigidState& s = m_start[k];
        const RigidState& e = m_end[k];
        b.position = s.x;
        b.orientation = s.rotation.orientation;
        b.endPosition = e.x;
        b.endOrientation = e.rotation.orientation;
        if (m_motion[k] != Motion::Awake)
            return; // static, or asleep: it does not move this step
        const Material& m = m_material[k];
        const dmat3 r = glm::mat3_cast(s.rotation.orientation);
        b.inverseInertia = r * m.inverseInertiaBody * glm::transpose(r);
        b.inertia = m_isPoint[k] ? dmat3(0.0) : glm::inverse(b.inverseInertia);
        b.inverseMass = m.inverseMass;
        b.driftWeight = m.driftWeight;
        b.v = e.v;
        b.w = b.inverseInertia * e.rotation.momentum;
        b.vStart = s.v;
        b.wStart = b.inverseInertia * s.rotation.momentum;
        b.vFree = b.v;
        b.wFree = b.w;
        m_energyStart[k] = energyInGravity(s, m.inverseMass, m.inverseInertiaBody, m_gravity);
        m_energyFree[k] = energyInGravity(e, m.inverseMass, m.inverseInertiaBody, m_gravity);
    }, kBodyGrain);
}

void RigidSystem::solveIsland(std::size_t island, const SolverSettings& settings)
{
    thread_local ContactSolver solver;
    thread_local JointSolver joints;
    const bool withJoints = !m_islands.links(island).empty();
    solver.prepare(m_cache.contacts(), m_islands.contacts(island), m_islands.bodies(island), m_solverBodies, settings,
                   withJoints);
    joints.prepare(m_joints, solvedLinks(island), m_solverBodies, settings, worldBody());
    if (withJoints)
        solveMechanismVelocities(solver, joints, settings);
    else // a heap's, or a few bodies'
        solver.solveVelocities(ContactSolver::kHeapStrikes, settings.contact.velocityIterations,
                               settings.maxVelocityIterations());
    joints.storeImpulses();
    solver.storeImpulses();
    moveEndPoses(island, solver, settings.dt);
    // The velocities are final: no contact may have added to the island's energy (capEnergy).
    // The position pass then moves the poses alone, adding no motion. The room is the boundary
    // nothing may leave: what is beyond it is taken back before the pass (so that the pass's
    // contacts are found where the bodies are) and after it, when what a body was lifted into
    // is pushed away from it.
    const auto bodies = m_islands.bodies(island);
    const double methodWork = joints.explicitSpringWork();
    capEnergy(island, methodWork);
    pushOutOfRoom(bodies);
    thread_local std::vector<Contact> atEnd;
    contactsAtEnd(island, atEnd);
    if (!withJoints)
        sweepPositions(island, solver, atEnd, settings.contact.positionIterations);
    for (int it = 0; withJoints && it < settings.contact.positionIterations; ++it) {
        joints.solvePositions();
        solver.solvePositions(atEnd);
    }
    if (withJoints)
        joints.holdExactly([&](BodyIndex k, std::vector<Contact>& out) { roomAtEnd({&k, 1}, out, 0.0); });
    thread_local std::vector<std::uint32_t> lifted;
    pushOutOfRoom(bodies, &lifted);
    if (!lifted.empty())
        solver.settleOn(atEnd, lifted, kSettleSweeps);
    // A joint does no work: what its position pass adds to the island's height is taken from its
    // motion (a chain's energy never grows). Not for contacts alone, whose pass only undoes an
    // overlap the step made, and whose resting bodies have no motion to take it from.
    if (withJoints) {
        joints.projectAtEnd(settings.contact.velocityIterations);
        capEnergy(island, methodWork);
    }
}

bool RigidSystem::appliedElsewhere(const Joint& j) const
{
    // A spring joint to a moving point is a spring of the point's own solve (XPBD's substeps,
    // xpbd_rigid_contacts.hpp; backward Euler's joint points, world_particle_systems.cpp):
    // applied here too, its force would count twice. (A fixed point is in neither solve, and its
    // joints stay here.)
    const auto inItsSolve = [&](BodyIndex k) {
        return k != kWorldBody && m_material[k].springJointsInItsSolve && m_material[k].inverseMass > 0.0;
    };
    return j.stiffness > 0.0 && (inItsSolve(j.a) || inItsSolve(j.b));
}

std::span<const std::uint32_t> RigidSystem::solvedLinks(std::size_t island) const
{
    const auto links = m_islands.links(island);
    const auto elsewhere = [&](std::uint32_t k) { return appliedElsewhere(m_joints[k]); };
    if (std::none_of(links.begin(), links.end(), elsewhere))
        return links;
    thread_local std::vector<std::uint32_t> solved;
    solved.clear();
    for (const std::uint32_t k : links)
        if (!elsewhere(k))
            solved.push_back(k);
    return solved;
}

void RigidSystem::sweepPositions(std::size_t island, ContactSolver& solver, std::vector<Contact>& atEnd, int sweeps)
{
    // The end poses' contacts reach contactMargin beyond each pair (and a struck body's pushes):
    // a body the sweeps moved further than half of that may have met one they did not hold (a
    // spinning die pushed out of its overlaps into a neighbour it had not reached), so its
    // contacts are found again and the island swept once more.
    const auto bodies = m_islands.bodies(island);
    thread_local std::vector<dvec3> before;
    before.clear();
    for (const std::uint32_t k : bodies)
        before.push_back(m_solverBodies[k].endPosition);
    solver.solvePositions(atEnd, sweeps);
    const std::size_t n = m_world.size();
    thread_local std::vector<std::uint8_t> moved; // by body, the room's two indices never
    if (moved.size() < n + 2)
        moved.resize(n + 2, 0);
    const double reach = 0.5 * m_settings.contactMargin;
    bool any = false;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const dvec3 d = m_solverBodies[bodies[i]].endPosition - before[i];
        moved[bodies[i]] = glm::dot(d, d) > reach * reach;
        any = any || moved[bodies[i]];
    }
    const auto forget = [&] { // all clear again for the next island's
        for (const std::uint32_t k : bodies)
            moved[k] = 0;
    };
    if (!any)
        return forget();
    thread_local std::vector<std::uint32_t> again;
    again.clear();
    for (const std::uint32_t index : m_islands.contacts(island)) {
        const Contact& c = m_cache.contacts()[index];
        if (c.b < n && (moved[c.a] || moved[c.b]))
            again.push_back(index);
    }
    std::erase_if(atEnd, [&](const Contact& c) { return c.b < n && (moved[c.a] || moved[c.b]); });
    contactsAtEnd({}, again, atEnd);
    forget();
    solver.solvePositions(atEnd, sweeps);
}

void RigidSystem::solveMechanismVelocities(ContactSolver& solver, JointSolver& joints, const SolverSettings& settings)
{
    // A mechanism (a chain, a cradle on its threads): its blows pass in full, and the joints'
    // sweeps take turns with the contacts'.
    solver.collide(joints);
    joints.warmStart();
    solver.warmStart();
    for (int it = 0; it < settings.maxVelocityIterations(); ++it) {
        joints.solveVelocities();
        const bool converged = solver.solveVelocities();
        if (converged && it + 1 >= settings.contact.velocityIterations)
            break;
    }
    solver.finishVelocities(&joints);
    joints.solveVelocitiesExactly();
}

void RigidSystem::moveEndPoses(std::size_t island, const ContactSolver& solver, double dt)
{
    // The velocity pass's impulses act from the start of the step: the end pose moves by the
    // part of the drift the end velocity drives.
    for (const std::uint32_t k : m_islands.bodies(island)) {
        SolverBody& b = m_solverBodies[k];
        const double drift = b.driftWeight * dt;
        const auto [v, w] = solver.afterCollisions(k);
        b.shift += (b.v - v) * drift;
        b.turn += (b.w - w) * drift;
        b.endPosition += b.shift;
        b.endOrientation = turnedByImpulses(b.orientation, b.endOrientation, b.turn, b.driftWeight);
    }
}

void RigidSystem::pushOutOfRoom(std::span<const std::uint32_t> bodies, std::vector<std::uint32_t>* moved)
{
    if (moved)
        moved->clear();
    const double slop = m_settings.linearSlop;
    // A ball of a rope or cloth too: it met the room by its own rule before this step's contacts,
    // and a heavy body driven into it can have pushed it through a wall since.
    for (const std::uint32_t k : bodies) {
        SolverBody& b = m_solverBodies[k];
        const dvec3 before = b.endPosition;
        rigid::pushOutOfRoom(*m_material[k].shape, b.endPosition, b.endOrientation, m_planes);
        const dvec3 d = b.endPosition - before;
        if (moved && glm::dot(d, d) > slop * slop) // more than what the position pass leaves
            moved->push_back(k);
    }
}

void RigidSystem::contactsAtEnd(std::size_t island, std::vector<Contact>& out) const
{
    // The narrow phase again, at the end poses, for the pairs that touched or could have and for
    // the island's bodies against the room: the position pass works on what overlaps now, the
    // room's surfaces in the same sweeps as the bodies (a die pushed down into the floor by the
    // one landing on it is pushed back up within the sweep, and the other one further away).
    out.clear();
    contactsAtEnd(m_islands.bodies(island), m_islands.contacts(island), out);
}

void RigidSystem::contactsAtEnd(std::span<const std::uint32_t> bodies, std::span<const std::uint32_t> contacts,
                                std::vector<Contact>& out) const
{
    // A large island's in fixed chunks on every core, joined in order: the same list on any.
    constexpr std::size_t kChunk = 128;
    const std::size_t bodyChunks = (bodies.size() + kChunk - 1) / kChunk;
    const std::size_t chunks = bodyChunks + (contacts.size() + kChunk - 1) / kChunk;
    if (chunks <= 2) {
        roomAtEnd(bodies, out);
        pairsAtEnd(contacts, out);
        return;
    }
    std::vector<std::vector<Contact>> found(chunks);
    // Isolated: a thread waiting here takes no other island's work, whose scratch it holds.
    tbb::this_task_arena::isolate([&] {
        tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t chunk) {
            if (chunk < bodyChunks)
                roomAtEnd(bodies.subspan(chunk * kChunk, std::min(kChunk, bodies.size() - chunk * kChunk)), found[chunk]);
            else {
                const std::size_t first = (chunk - bodyChunks) * kChunk;
                pairsAtEnd(contacts.subspan(first, std::min(kChunk, contacts.size() - first)), found[chunk]);
            }
        });
    });
    for (const auto& part : found)
        out.insert(out.end(), part.begin(), part.end());
}

double RigidSystem::positionMargin(BodyIndex a, BodyIndex b) const
{
    // Not only what overlaps: what the sweeps push together (a die pushed up out of the floor
    // into the one above it) must be there for them to push apart again, and a body struck in
    // the step may have come as far again as its partners could push it (widenForPushes).
    const auto push = [&](BodyIndex k) { return k < m_push.size() ? m_push[k].length : 0.0; };
    return m_settings.contactMargin + push(a) + push(b);
}

void RigidSystem::roomAtEnd(std::span<const std::uint32_t> bodies, std::vector<Contact>& out,
                            std::optional<double> margin) const
{
    const std::size_t n = m_world.size();
    for (const std::uint32_t k : bodies) {
        if (m_isPoint[k])
            continue;
        const SolverBody& b = m_solverBodies[k];
        const std::size_t first = out.size();
        collideWithRoom(*m_material[k].shape, Transform{b.endPosition, glm::mat3_cast(b.endOrientation)}, m_planes,
                        margin.value_or(positionMargin(k, BodyIndex(n + 1))), BodyIndex(k), BodyIndex(n + 1), out);
        for (std::size_t e = first; e < out.size(); ++e)
            out[e].radiusA = sphereRadius(*m_material[k].shape);
    }
}

void RigidSystem::pairsAtEnd(std::span<const std::uint32_t> contacts, std::vector<Contact>& out) const
{
    const std::size_t n = m_world.size();
    for (const std::uint32_t index : contacts) {
        const Contact& c = m_cache.contacts()[index];
        if (c.b >= n)
            continue;
        const SolverBody& a = m_solverBodies[c.a];
        const SolverBody& b = m_solverBodies[c.b];
        const Transform ta{a.endPosition, glm::mat3_cast(a.endOrientation)};
        const Transform tb{b.endPosition, glm::mat3_cast(b.endOrientation)};
        Contact& e = out.emplace_back();
        e.a = c.a;
        e.b = c.b;
        e.radiusA = c.radiusA;
        e.radiusB = c.radiusB;
        const CollisionShape& shapeB = *m_material[c.b].shape;
        const double margin = positionMargin(c.a, c.b);
        if (!carryManifold(c, ta, a.endOrientation, tb, b.endOrientation, shapeB.boundingRadius(), margin,
                           e)) {
            contact::SatCache sat = c.sat;
            e.takePoints(contact::collide(*m_material[c.a].shape, ta, shapeB, tb, margin, &sat));
        }
        if (e.count == 0)
            out.pop_back();
    }
}

void RigidSystem::capEnergy(std::size_t island, double methodWork)
{
    // No contact leaves an island with more energy than it started the step with, or would have
    // ended it with untouched: what the linearised contacts and the push-outs would add is taken
    // from its motion (every velocity scaled alike, which keeps the motion's direction). Never
    // from its height: lowering a resting stack by what the position pass raised it would sink
    // it a little every step.
    const auto bodies = m_islands.bodies(island);
    double start = 0.0, free = 0.0, end = 0.0, kinetic = 0.0;
    for (const std::uint32_t k : bodies) {
        const SolverBody& b = m_solverBodies[k];
        const Material& m = m_material[k];
        const RigidState s{b.endPosition, b.v, Rotation{b.endOrientation, m_end[k].rotation.momentum + b.momentumChange()}};
        start += m_energyStart[k];
        free += m_energyFree[k];
        const double e = energyInGravity(s, m.inverseMass, m.inverseInertiaBody, m_gravity);
        end += e;
        kinetic += e + glm::dot(m_gravity, s.x) / m.inverseMass;
    }
    // A spring joint's energy is the island's too: what it stores is not a gain.
    const Energies springs = springEnergy(island);
    start += springs.start;
    free += springs.free + methodWork;
    end += springs.end;
    const double excess = end - std::max(start, free);
    if (!(excess > 0.0)) // a NaN too: the finite check names the body
        return;
    // An island that nothing holds keeps its momentum: the excess is taken from its motion about
    // its centre of mass (three bodies on two springs in zero g lost a seventh of it in 3 s
    // otherwise).
    dvec3 momentum(0.0);
    double mass = 0.0;
    if (heldByNothing(island))
        for (const std::uint32_t k : bodies) {
            momentum += m_solverBodies[k].v / m_material[k].inverseMass;
            mass += 1.0 / m_material[k].inverseMass;
        }
    // Where the motion about the centre is less than the excess, all of it goes and the island
    // moves on as one: its momentum is not the contacts' to take (two bodies on a spring joint in
    // zero g stopped dead otherwise).
    const dvec3 centre = mass > 0.0 ? momentum / mass : dvec3(0.0);
    const double about = kinetic - 0.5 * mass * glm::dot(centre, centre);
    const bool aboutCentre = mass > 0.0;
    const double keep = aboutCentre ? (about > excess ? std::sqrt(1.0 - excess / about) : 0.0)
                                    : (kinetic > excess ? std::sqrt(1.0 - excess / kinetic) : 0.0);
    const dvec3 kept = aboutCentre ? centre : dvec3(0.0);
    for (const std::uint32_t k : bodies) {
        SolverBody& b = m_solverBodies[k];
        b.v = kept + (b.v - kept) * keep;
        b.w *= keep; // L = I w: scaled alike
    }
}

bool RigidSystem::heldByNothing(std::size_t island) const
{
    const auto movable = [&](BodyIndex k) { return k < m_world.size() && m_motion[k] == Motion::Awake; };
    for (const std::uint32_t index : m_islands.contacts(island)) {
        const Contact& c = m_cache.contacts()[index];
        if (!movable(c.a) || !movable(c.b))
            return false;
    }
    for (const std::uint32_t index : m_islands.links(island)) {
        const Joint& j = m_joints[index];
        if (!movable(j.a) || !movable(j.b))
            return false;
    }
    return true;
}

RigidSystem::Energies RigidSystem::springEnergy(std::size_t island) const
{
    Energies e;
    enum class When { Start, Free, End };
    auto pose = [&](BodyIndex k, When when) -> std::pair<dvec3, dquat> {
        if (k == kWorldBody)
            return {dvec3(0.0), dquat(1.0, 0.0, 0.0, 0.0)};
        if (when == When::End)
            return {m_solverBodies[k].endPosition, m_solverBodies[k].endOrientation};
        const RigidState& s = when == When::Start ? m_start[k] : m_end[k];
        return {s.x, s.rotation.orientation};
    };
    for (const std::uint32_t index : m_islands.links(island)) {
        const Joint& j = m_joints[index];
        if (j.type != JointType::Distance || !(j.stiffness > 0.0))
            continue;
        auto energy = [&](When when) {
            const auto [xa, qa] = pose(j.a, when);
            const auto [xb, qb] = pose(j.b, when);
            const double stretch = glm::length((xb + qb * j.localB) - (xa + qa * j.localA)) - j.length;
            return 0.5 * j.stiffness * stretch * stretch;
        };
        const double start = energy(When::Start);
        e.start += start;
        // The free step leaves out a spring that this solve applies. Under a Verlet-type method
        // (which drifts by the mean of the start and end velocities) the spring then keeps its
        // energy exactly, and its stretch at the free step's end, with no pull that it would have
        // had, is no energy the island could have had: counted, it let a hinged chain hanging on
        // a spring gain 4 times its energy. Under semi-implicit Euler the soft spring's own
        // backward Euler takes energy, and the free stretch leaves room for the swing of its
        // energy that the method makes, which capped every step would drain.
        // Between forward Euler's bodies (or one and the world) the spring is all explicit: its
        // start's impulse moves nothing in the step, so the free step's stretch is the end's, and
        // the kinetic energy the impulse gives is the method's (explicitSpringWork).
        const auto drifts = [&](BodyIndex k) { return k != kWorldBody && m_material[k].driftWeight < 1.0; };
        const auto explicitEnd = [&](BodyIndex k) {
            return k == kWorldBody || m_material[k].inverseMass == 0.0 || m_material[k].driftWeight == 0.0;
        };
        const bool explicitSpring = explicitEnd(j.a) && explicitEnd(j.b);
        e.free += appliedElsewhere(j) || explicitSpring || !(drifts(j.a) || drifts(j.b)) ? energy(When::Free) : start;
        e.end += energy(When::End);
    }
    return e;
}

void RigidSystem::holdNets(const SolverSettings& settings)
{
    if (m_segments.empty())
        return;
    thread_local std::vector<PieceContact> contacts;
    thread_local std::vector<std::uint32_t> balls;
    contacts.clear();
    balls.clear();
    for (const Segment& s : m_segments)
        segmentContacts(s, contacts, balls);
    for (const auto& t : m_triangles)
        triangleContacts(t, contacts, balls);
    if (contacts.empty())
        return;
    constexpr int kSweeps = 4;
    holdPieces(contacts, m_solverBodies, settings.restingSpeed, settings.dt, kSweeps);
    // A ball pushed off a body may have been pushed through a wall: the room is the boundary.
    std::sort(balls.begin(), balls.end());
    balls.erase(std::unique(balls.begin(), balls.end()), balls.end());
    pushOutOfRoom(balls);
}

void RigidSystem::segmentContacts(const Segment& s, std::vector<PieceContact>& out,
                                  std::vector<std::uint32_t>& balls) const
{
    // A net stepped by XPBD meets the bodies by its balls inside its substeps, and no more.
    if (m_material[s.a].metInSubsteps || m_material[s.b].metInSubsteps)
        return;
    const SolverBody& a = m_solverBodies[s.a];
    const SolverBody& b = m_solverBodies[s.b];
    const Material& ma = m_material[s.a];
    const Material& mb = m_material[s.b];
    const double ra = sphereRadius(*ma.shape), rb = sphereRadius(*mb.shape);
    const double reach = std::max(ra, rb);
    thread_local std::vector<BodyPair> partners;
    partners.clear();
    m_broadPhase.partnersOf(
        s.a, {glm::min(a.endPosition, b.endPosition) - reach, glm::max(a.endPosition, b.endPosition) + reach}, m_boxes,
        m_isPoint, partners);
    for (const BodyPair& pair : partners) {
        const std::uint32_t k = pair.a == s.a ? pair.b : pair.a;
        if (m_isPoint[k] || joinedApart(s.a, k) || joinedApart(s.b, k))
            continue;
        const SolverBody& body = m_solverBodies[k];
        const SegmentDepths depths =
            deepestBetweenBalls(*m_material[k].shape, Transform{body.endPosition, glm::mat3_cast(body.endOrientation)},
                                a.endPosition, ra, b.endPosition, rb, m_settings.contactMargin);
        for (int point = 0; point < depths.count; ++point) {
            const SegmentDepth& depth = depths.points[std::size_t(point)];
            out.push_back(pieceContact({s.a, s.b, s.b}, {1.0 - depth.t, depth.t, 0.0}, k, depth.normal, depth.point,
                                       depth.separation, depth.line));
        }
        if (depths.count > 0) {
            balls.push_back(s.a);
            balls.push_back(s.b);
        }
    }
}

void RigidSystem::triangleContacts(const std::array<std::uint32_t, 3>& t, std::vector<PieceContact>& out,
                                   std::vector<std::uint32_t>& balls) const
{
    for (const std::uint32_t end : t)
        if (m_material[end].metInSubsteps)
            return;
    std::array<dvec3, 3> x{};
    std::array<double, 3> r{};
    dvec3 lo(INFINITY), hi(-INFINITY);
    for (std::size_t e = 0; e < 3; ++e) {
        x[e] = m_solverBodies[t[e]].endPosition;
        r[e] = sphereRadius(*m_material[t[e]].shape);
        lo = glm::min(lo, x[e] - r[e]);
        hi = glm::max(hi, x[e] + r[e]);
    }
    thread_local std::vector<BodyPair> partners;
    partners.clear();
    m_broadPhase.partnersOf(t[0], {lo, hi}, m_boxes, m_isPoint, partners);
    for (const BodyPair& pair : partners) {
        const std::uint32_t k = pair.a == t[0] ? pair.b : pair.a;
        if (m_isPoint[k] || joinedApart(t[0], k) || joinedApart(t[1], k) || joinedApart(t[2], k))
            continue;
        const SolverBody& body = m_solverBodies[k];
        const std::optional<TriangleDepth> depth =
            deepestUnderTriangle(*m_material[k].shape, Transform{body.endPosition, glm::mat3_cast(body.endOrientation)}, x,
                                 r, m_settings.contactMargin);
        if (!depth)
            continue;
        out.push_back(pieceContact(t, depth->weights, k, depth->normal, depth->point, depth->separation, depth->line));
        balls.insert(balls.end(), t.begin(), t.end());
    }
}

PieceContact RigidSystem::pieceContact(const std::array<std::uint32_t, 3>& ends, const std::array<double, 3>& weights,
                                       std::uint32_t body, const dvec3& normal, const dvec3& point, double separation,
                                       double line) const
{
    PieceContact c;
    c.ends = ends;
    c.weights = weights;
    c.body = body;
    c.normal = normal;
    c.arm = point - m_solverBodies[body].endPosition;
    c.depth = std::max(0.0, std::min(line, 0.0) - separation);
    c.gap = std::max(separation, 0.0);
    // The point's material: its balls' by their weights, with the body's by the rule.
    double friction = 0.0, restitution = 0.0;
    for (std::size_t e = 0; e < 3; ++e) {
        friction += weights[e] * m_material[ends[e]].friction;
        restitution += weights[e] * m_material[ends[e]].restitution;
    }
    c.friction = detail::combinedFriction(friction, m_material[body].friction);
    c.restitution = detail::combinedRestitution(restitution, m_material[body].restitution);
    return c;
}

void RigidSystem::finishBodies()
{
    detail::forEachIndex(m_world.size(), [&](std::size_t k) {
        if (m_motion[k] != Motion::Awake)
            return;
        const SolverBody& b = m_solverBodies[k];
        RigidState& e = m_end[k];
        e.x = b.endPosition;
        e.v = b.v;
        e.rotation.orientation = b.endOrientation;
        e.rotation.momentum += b.momentumChange();
    }, kBodyGrain);
}

void RigidSystem::updateSleep(double dt)
{
    if (!m_settings.sleeping)
        return;
    const std::size_t n = m_world.size();
    for (std::size_t k = 0; k < n; ++k) {
        if (m_motion[k] != Motion::Awake || m_isPoint[k])
            continue;
        const RigidState& e = m_end[k];
        const double spin = glm::length(worldAngularVelocity(e, m_material[k].inverseInertiaBody));
        const double speed = std::max(glm::length(e.v), spin * m_material[k].shape->boundingRadius());
        m_stillFor[k] = speed < m_settings.sleepSpeed ? m_stillFor[k] + dt : 0.0;
    }
    for (std::size_t island = 0; island < m_islands.count(); ++island) {
        const auto bodies = m_islands.bodies(island);
        const bool still = std::all_of(bodies.begin(), bodies.end(),
                                       [&](std::uint32_t k) { return m_stillFor[k] >= m_settings.timeToSleep; });
        if (!still)
            continue;
        // Reuse an emptied slot, so that a pile that wakes and sleeps does not grow the list.
        std::uint32_t slot = 0;
        while (slot < m_sleepingIslands.size() && !m_sleepingIslands[slot].empty())
            ++slot;
        if (slot == m_sleepingIslands.size())
            m_sleepingIslands.emplace_back();
        m_sleepingIslands[slot].assign(bodies.begin(), bodies.end());
        for (const std::uint32_t k : bodies) {
            m_motion[k] = Motion::Asleep;
            m_sleepingIsland[k] = slot;
            m_end[k].v = dvec3(0.0);
            m_end[k].rotation.momentum = dvec3(0.0);
        }
    }
}

void RigidSystem::solve(const dvec3& gravity, double dt)
{
    m_gravity = gravity;
    if (!anythingAwake()) {
        m_islands.build(m_motion, {}, {});
        return;
    }
    prepareBodies(dt, m_surfaces);
    m_links.resize(m_joints.size());
    for (std::size_t k = 0; k < m_joints.size(); ++k)
        m_links[k] = {m_joints[k].a, m_joints[k].b};
    m_islands.build(m_motion, m_cache.contacts(), m_links);
    SolverSettings settings;
    settings.dt = dt;
    settings.restingSpeed = 2.0 * glm::length(gravity) * dt;
    settings.contact = m_settings;
    // The largest island a task of its own, started at once, while the other cores take the rest
    // (a heap's one island of 800 dice and its few loose dice: in index order a core could solve
    // the heap after a run of small ones while the other had nothing left). Islands share no
    // moving body: the order changes no result.
    m_islandOrder.resize(m_islands.count());
    for (std::size_t k = 0; k < m_islandOrder.size(); ++k)
        m_islandOrder[k] = std::uint32_t(k);
    std::stable_sort(m_islandOrder.begin(), m_islandOrder.end(), [&](std::uint32_t p, std::uint32_t q) {
        return m_islands.contacts(p).size() + m_islands.links(p).size() >
               m_islands.contacts(q).size() + m_islands.links(q).size();
    });
    if (!m_islandOrder.empty())
        tbb::parallel_invoke([&] { solveIsland(m_islandOrder[0], settings); },
                             [&] {
                                 tbb::parallel_for(std::size_t(1), m_islandOrder.size(),
                                                   [&](std::size_t k) { solveIsland(m_islandOrder[k], settings); });
                             });
    holdNets(settings);
    finishBodies();
    updateSleep(dt);
}

void RigidSystem::keepAwake(std::size_t k)
{
    if (m_motion[k] == Motion::Asleep)
        wakeIsland(std::uint32_t(k));
    m_stillFor[k] = 0.0;
}

void RigidSystem::wakeAll()
{
    for (std::size_t k = 0; k < m_motion.size(); ++k)
        if (m_motion[k] == Motion::Asleep) {
            m_motion[k] = Motion::Awake;
            m_stillFor[k] = 0.0;
            m_sleepingIsland[k] = Islands::npos;
        }
    m_sleepingIslands.clear();
}

} // namespace pba::rigid
