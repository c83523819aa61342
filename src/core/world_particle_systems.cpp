// A World's phase for its particle systems (integrateParticleSystems): each system of the
// coupling with its method. integrateCoupled steps the explicit methods' systems, every stage
// evaluating every force; integrateBackwardEuler and integrateXpbd the systems whose springs
// are stepped implicitly, with their solvers (src/core/particle_systems/backward_euler.cpp, xpbd.cpp). Each
// hands the end states to collideAndStore.
#include "pba/world.hpp"

#include <algorithm>
#include <optional>
#include <tuple>
#include <unordered_map>

#include "surfaces/collision_rules.hpp"
#include "swarms/grain_contacts.hpp"
#include "material_rule.hpp"
#include "parallel.hpp"
#include "balls/particle_contacts.hpp"
#include "rigid/rigid_system.hpp"
#include "particle_systems/spring_neighbours.hpp"
#include "particle_systems/spring_solvers.hpp"
#include "world_checks.hpp"

namespace pba {

namespace {

/// Two balls further apart than this many of their radii's sum no longer hold one on the other,
/// nor one whose centre is lower than this cosine from straight above the other's.
constexpr double kBallsHeldWithin = 1.01;
constexpr double kBallsHeldAbove = 0.7;

/// A member joined to a fixed body answers its springs as if this many times heavier: pinned.
constexpr double kPinnedMassRatio = 1e9;

/// A rigid body's point that a spring joint ties a member to, solved as one more member: where
/// it is (less the member's own offset to its anchor, so that the spring runs between the two
/// members), how fast it moves, and the mass it answers with: the body's at that point, K^-1 with
/// K = 1/m I - [r] I^-1 [r] (its velocity's change for an impulse there), shared among the
/// body's `sharing` points in the system; as pinned for a fixed body.
struct JointPoint {
    dvec3 x{0.0}, v{0.0};
    dmat3 mass{0.0};
};
JointPoint jointPoint(const RigidBody& body, const dvec3& arm, const dvec3& offset, double memberMass,
                      std::size_t sharing)
{
    const dvec3 point = body.getPos() + arm;
    if (body.isFixed())
        return {point - offset, dvec3(0.0), dmat3(kPinnedMassRatio * memberMass)};
    const dmat3 turn = glm::mat3_cast(body.getOrientation());
    const dmat3 inverseInertia = turn * body.getInverseInertiaBody() * glm::transpose(turn);
    const dmat3 across(dvec3(0.0, arm.z, -arm.y), dvec3(-arm.z, 0.0, arm.x), dvec3(arm.y, -arm.x, 0.0));
    const dmat3 k = dmat3(1.0 / body.getMass()) - across * inverseInertia * across;
    return {point - offset, body.getVel() + glm::cross(body.getAngularVelocity(), arm),
            glm::inverse(k) / double(sharing)};
}

/// Backward Euler's step of a system's members (x, v) and its joint points (addJointPoints).
void solveWithJointPoints(detail::SpringSolver& solver, std::span<dvec3> x, std::span<dvec3> v, double dt)
{
    const bool points = !solver.pointX.empty();
    if (points) {
        solver.wholeX.assign(x.begin(), x.end());
        solver.wholeX.insert(solver.wholeX.end(), solver.pointX.begin(), solver.pointX.end());
        solver.wholeV.assign(v.begin(), v.end());
        solver.wholeV.insert(solver.wholeV.end(), solver.pointV.begin(), solver.pointV.end());
    }
    solver.backwardEuler.step(solver.solvedSprings(), solver.solveMass, points ? solver.wholeX : x,
                              points ? solver.wholeV : v, solver.startForces, dt, solver.heldOn,
                              {solver.bearerOf, solver.bearerArm, solver.bearers}, solver.directionalMass);
    if (!points)
        return;
    std::copy_n(solver.wholeX.begin(), x.size(), x.begin());
    std::copy_n(solver.wholeV.begin(), v.size(), v.begin());
    std::copy(solver.wholeV.begin() + std::ptrdiff_t(v.size()), solver.wholeV.end(), solver.pointV.begin());
}

/// How fast a member may move along a surface's normal and still rest on it (the rule after the
/// step's resting contact): twice what its acceleration gives it in a step.
double restingReach(const dvec3& acceleration, double dt)
{
    return 2.0 * glm::length(acceleration) * dt;
}

/// A contact's deepest point.
const rigid::ContactPoint& deepestPoint(const rigid::Contact& c)
{
    return *std::min_element(c.points.begin(), c.points.begin() + c.count,
                             [](const auto& p, const auto& q) { return p.separation < q.separation; });
}

/// Body i's place among a system's members (listed in increasing order), or members.size().
std::size_t placeAmong(const std::vector<std::size_t>& members, std::size_t i)
{
    const auto it = std::lower_bound(members.begin(), members.end(), i);
    return it != members.end() && *it == i ? std::size_t(it - members.begin()) : members.size();
}

/// How a joint between a member of a system and a rigid body enters backward Euler's solve: the
/// member carries the body's mass at a ball joint (World::carryJoinedBodies), and pinned along a
/// rod to a fixed body; a spring joint's or a rod's body point is one more member of the solve
/// (addJointPoints). A rod whose ends collide is left to the joint solver and the contacts.
using Link = detail::SpringSolver::Link;
std::vector<Link> linksInTheSolve(const rigid::RigidSystem& system, const std::vector<ClonePtr<Body>>& bodies,
                                  const std::vector<std::size_t>& members)
{
    std::vector<Link> links;
    for (std::size_t i = 0; i < system.joints().size(); ++i) {
        const rigid::Joint& j = system.joints()[i];
        if (j.b == rigid::kWorldBody || system.isPoint(j.a) == system.isPoint(j.b))
            continue;
        const bool pointIsA = system.isPoint(j.a);
        const std::size_t k = placeAmong(members, system.worldIndex(pointIsA ? j.a : j.b));
        const std::size_t body = system.worldIndex(pointIsA ? j.b : j.a);
        const bool rod = j.type == JointType::Distance && j.length > 0.0 && !(j.stiffness > 0.0);
        if (k == members.size() || (rod && j.collide))
            continue;
        const bool fixed = bodies[body]->isFixed();
        const Link::Kind kind = j.stiffness > 0.0 ? Link::Point
                                : rod            ? (fixed ? Link::PinnedAlongRod : Link::Point)
                                                 : Link::Carried;
        links.push_back({kind, i, k, body, !fixed});
    }
    // A body with points in the solve is shared by them and by the particles carrying it; a body
    // only carried is carried whole by each (sharing it, a 52 kg ball on two ball joints from a
    // light cloth gained 1.48 times its energy at 1/60 s, where carried whole 1.09).
    // (Counted by body, once: a cloth may hang hundreds of bodies.)
    std::unordered_map<std::size_t, std::pair<std::size_t, std::size_t>> counts; // body: points, links sharing it
    for (const Link& l : links)
        if (l.kind != Link::PinnedAlongRod) {
            auto& [points, sharing] = counts[l.body];
            points += l.kind == Link::Point ? 1 : 0;
            ++sharing;
        }
    for (Link& l : links)
        if (l.kind != Link::PinnedAlongRod && counts[l.body].first > 0)
            l.sharing = counts[l.body].second;
    return links;
}

/// The mass `mass` (a 3 x 3 matrix) answers with along unit direction u.
double massAlong(const dmat3& mass, const dvec3& u)
{
    return 1.0 / glm::dot(u, glm::inverse(mass) * u);
}

/// A rod as a spring of the solve, and the springs that hold a body's points in the solve at their
/// distances: dt^2 k this many times the mass of the body's point along it (of the lighter end,
/// for two points), so that a rod stretches by g dt^2 / 10 under the body's weight. Stiffer, the
/// solve's residual (its tolerance is relative) grows with the spring's force, and so does the
/// momentum it loses: a free sphere on a rod to a rope drifted by 1.6e-4 of its momentum at 100
/// times, 3e-6 at 10. The joint solver after the step holds the rod exactly.
constexpr double kStiffLinkRatio = 10.0;

/// A spring joint's or a rod's body point is one more member of the solve, after the system's own,
/// with the body's mass at that point and its weight, tied to the member by the joint's spring
/// (a rod: a stiff spring): the two sides then answer it implicitly together, and the body takes
/// what the solve gave its point (World::pushCarriedBodies). Applied after the member's solve, the
/// spring yanked a rope's light end with a crate's weight (14 times the energy at 1/60 s), and a
/// rope's end swinging about a crate on a 3 cm rod, carried along the rod's start direction,
/// gained 73 times its energy at 1/60 s.
void addJointPoints(const rigid::RigidSystem& system, const std::vector<ClonePtr<Body>>& bodies,
                   const std::vector<std::size_t>& members, std::span<const dvec3> x, std::span<const dvec3> v,
                   std::span<const double> mass, const dvec3& gravity, double dt, detail::SpringSolver& solver)
{
    const std::size_t n = members.size();
    for (const Link& l : solver.links) {
        if (l.kind != Link::Point)
            continue;
        rigid::Joint j = system.joints()[l.joint];
        const bool pointIsA = system.isPoint(j.a);
        const auto& body = static_cast<const RigidBody&>(*bodies[l.body]);
        const dvec3 arm = body.getOrientation() * (pointIsA ? j.localB : j.localA);
        const JointPoint p = jointPoint(body, arm, pointIsA ? j.localA : j.localB, mass[l.member], l.sharing);
        const dvec3 u = unitOrZero(p.x - x[l.member]);
        if (!(j.stiffness > 0.0)) // a rod
            j.stiffness = u == dvec3(0.0) ? 0.0 : kStiffLinkRatio * massAlong(p.mass, u) / (dt * dt);
        const auto point = std::uint32_t(n + solver.pointX.size());
        solver.pointX.push_back(p.x);
        solver.pointV.push_back(p.v);
        solver.pointBody.push_back(l.moves ? l.body : detail::SpringSolver::kNoBody);
        solver.jointSprings.push_back({std::uint32_t(l.member), point, j.stiffness, j.length, j.damping});
        // The spring's force at the start, on both ends (the solve's forces include its springs').
        const dvec3 pull = (j.stiffness * (glm::length(p.x - x[l.member]) - j.length) +
                            j.damping * glm::dot(u, p.v - v[l.member])) * u;
        solver.startForces[l.member] += pull;
        solver.startForces.push_back(body.isFixed() ? -pull : p.mass * gravity - pull);
        solver.solveMass.push_back(0.0);
        if (solver.directionalMass.empty())
            solver.directionalMass.assign(n, dmat3(0.0));
        solver.directionalMass.push_back(p.mass);
        solver.heldOn.push_back(dvec3(0.0));
        solver.bearerOf.push_back(detail::BackwardEuler::kNoBearer);
        solver.bearerArm.push_back(dvec3(0.0));
        if (!body.isFixed())
            solver.carried.push_back({point, l.body, 1.0, p.mass, arm, p.v});
    }
}

/// A moving body with several points in the solve (and the particles carrying it beside them)
/// moves them as one: each pair is held at its distance by a stiff spring (kStiffLinkRatio), so
/// that two ropes pulling a light box apart meet its whole mass, not each its own share of it
/// (1.8 times the energy).
void linkPointsOfABody(std::span<const dvec3> x, double dt, detail::SpringSolver& solver)
{
    const std::size_t n = x.size();
    struct Node {
        std::size_t body;
        std::uint32_t index; ///< a member's, or a point's (n and beyond)
    };
    std::vector<Node> nodes;
    for (const Link& l : solver.links)
        if (l.kind == Link::Carried && l.moves && l.sharing > 1)
            nodes.push_back({l.body, std::uint32_t(l.member)});
    for (std::size_t i = 0; i < solver.pointBody.size(); ++i)
        if (solver.pointBody[i] != detail::SpringSolver::kNoBody)
            nodes.push_back({solver.pointBody[i], std::uint32_t(n + i)});
    const auto at = [&](std::uint32_t i) { return i < n ? x[i] : solver.pointX[i - n]; };
    const auto weighs = [&](std::uint32_t i, const dvec3& u) {
        return i < n ? solver.solveMass[i] : massAlong(solver.directionalMass[i], u);
    };
    // Each body's nodes side by side, in a fixed order, and each pair of one body's once.
    std::sort(nodes.begin(), nodes.end(),
              [](const Node& a, const Node& b) { return std::tie(a.body, a.index) < std::tie(b.body, b.index); });
    for (std::size_t a = 0; a < nodes.size(); ++a)
        for (std::size_t b = a + 1; b < nodes.size() && nodes[b].body == nodes[a].body; ++b) {
            const dvec3 d = at(nodes[b].index) - at(nodes[a].index);
            const dvec3 u = unitOrZero(d);
            if (u == dvec3(0.0))
                continue;
            const double lighter = std::min(weighs(nodes[a].index, u), weighs(nodes[b].index, u));
            solver.jointSprings.push_back(
                {nodes[a].index, nodes[b].index, kStiffLinkRatio * lighter / (dt * dt), glm::length(d), 0.0});
        }
}

/// The normal of the surface backward Euler holds a member on for the step (or zero): the first of
/// its room's planes it is within `depth` of, moving along the normal no faster than `reach` (m/s)
/// either way (the resting contact of afterStepWithFriction), and not over a hole.
dvec3 restingOn(std::span<const Plane> room, const dvec3& x, const dvec3& v, double reach, double depth)
{
    for (const Plane& plane : room)
        if (std::abs(plane.distance(x)) <= std::max(collision_detail::contactTolerance(plane), depth) &&
            std::abs(plane.along(v)) <= reach && !plane.overHole(x))
            return plane.normal;
    return dvec3(0.0);
}

/// The members with a radius that may touch in the step, each reaching as far as it may move (its
/// speed, and a quarter of its radius for what the step adds), but for those the springs hold near
/// each other (`near`, by world index).
template <class Near>
std::span<const detail::Xpbd::Touching> touchingMembers(detail::SpringSolver& solver, std::span<const dvec3> x,
                                                         std::span<const dvec3> v, std::span<const std::size_t> members,
                                                         Near&& near, double dt)
{
    solver.touching.clear();
    const auto reach = [&](std::size_t k) {
        return solver.radius[k] > 0.0 ? 1.25 * solver.radius[k] + glm::length(v[k]) * dt : 0.0;
    };
    double largest = 0.0;
    for (std::size_t k = 0; k < members.size(); ++k)
        largest = std::max(largest, reach(k));
    if (!(largest > 0.0))
        return {};
    solver.grid.findPairs(members.size(), [&](std::size_t k) { return x[k]; }, reach, largest, solver.candidates);
    for (const auto& [a, b] : solver.candidates)
        if (solver.radius[a] > 0.0 && solver.radius[b] > 0.0 && !near(members[a], members[b]))
            solver.touching.push_back({a, b, solver.radius[a] + solver.radius[b],
                                       detail::combinedFriction(solver.friction[a], solver.friction[b])});
    return solver.touching;
}

} // namespace

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
    if (!x.empty())
        detail::forEachIndex(members.size(), [&](std::size_t k) { m_bodies.trial[members[k]] = State{x[k], v[k]}; });
    sumForcesOnMembers(members, wanted, m_forces.sums,
                       [constraints](std::size_t f) { return !constraints || !constraints->isSpring(f); });
}

void World::sumForcesOnMembers(const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted,
                               std::vector<dvec3>& sums, const std::function<bool(std::size_t)>& keep)
{
    sums.resize(m_bodies.objects.size());
    detail::forEachIndex(members.size(), [&](std::size_t k) { sums[members[k]] = dvec3(0.0); });
    const BodyStates in{m_bodies.objects, m_bodies.trial, wanted, m_bodies.masses, {}, m_bodies.radii};
    Accumulators out{sums, {}, &m_forces.scratch};
    for (std::size_t f = 0; f < m_forces.objects.size(); ++f)
        if (keep(f))
            m_forces.objects[f]->accumulate(in, out);
}

void World::integrateCoupled(Integrator integrator, const std::vector<std::size_t>& members,
                             std::span<const std::uint8_t> wanted, double dt)
{
    const std::size_t n = members.size();
    CoupledScratch& s = m_particleSystems.scratch;
    startSystem(members);
    const bool book = !m_bodies.sourceWork.empty();
    if (book)
        s.sourceImpulse.assign(n, dvec3(0.0));
    const std::span<const double> weights = stageWeights(integrator);
    std::size_t stage = 0;
    bool first = true;
    auto accel = [&](const Vec3Array& xs, const Vec3Array& vs) {
        sumSystemForces(members, wanted, std::span<const dvec3>(xs.begin(), n), std::span<const dvec3>(vs.begin(), n),
                        nullptr);
        if (book)
            bookSourceStage(members, wanted, weights[std::min(stage++, weights.size() - 1)]);
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
    if (book) // (the free flight's end: the contacts after it are not the sources')
        detail::forEachIndex(n, [&](std::size_t k) {
            const dvec3 mean = 0.5 * (m_bodies.previous[members[k]].vel + s.v[k]);
            m_bodies.sourceWork[members[k]] = dt * glm::dot(s.sourceImpulse[k], mean);
        });
    collideAndStore(members, dt, integrator);
}

void World::bookSourceStage(const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted,
                            double weight)
{
    // The sources once more, alone, where sumSystemForces left the members (m_bodies.trial): the
    // sums themselves keep their order, so a world's results do not depend on the book.
    sumForcesOnMembers(members, wanted, m_forces.sourceSums,
                       [this](std::size_t f) { return m_forces.objects[f]->addsEnergy(); });
    CoupledScratch& s = m_particleSystems.scratch;
    detail::forEachIndex(members.size(), [&](std::size_t k) {
        s.sourceImpulse[k] += weight * m_forces.sourceSums[members[k]];
    });
}

void World::collideAndStore(const std::vector<std::size_t>& members, double dt, Integrator integrator)
{
    // Collisions, the bodies' new states and the check that they are finite in one pass, so
    // each body's object is visited once here: a cloth's bodies are many and far apart.
    const std::span<const Plane> planes(m_surfaces.planes);
    const CoupledScratch& s = m_particleSystems.scratch;
    // As a rigid body's impulses move its end pose; backward Euler holds its resting members in
    // its solve, and rubs them there.
    const double drift = integrator == Integrator::ImplicitEuler ? 0.0 : rigid::driftWeight(integrator) * dt;
    const std::size_t bad = detail::lowestFailing(members, 2048, m_bodies.objects.size(), [&](std::size_t k) {
        const std::size_t i = members[k];
        State end{s.x[k], s.v[k]};
        std::array<Plane, kMaxBallPlanes> room;
        const auto ball = ballPlanes(planes, m_bodies.radii[i], room);
        if (!planes.empty())
            m_bodies.bounces[i] += static_cast<std::uint64_t>(
                afterStepWithFriction(coupledCollisionResponse(), ball, m_bodies.cors[i], m_bodies.frictions[i],
                                      glm::length(s.acc[k]) * dt, m_bodies.previous[i].pos, end.pos,
                                      end.vel, std::optional(drift)));
        Body& b = *m_bodies.objects[i];
        b.setState(end);
        b.setAcc(s.acc[k]);
        return detail::isFinite(end.pos) && detail::isFinite(end.vel);
    });
    m_bodies.firstNonFinite = std::min(m_bodies.firstNonFinite, bad);
}

detail::SpringSolver& World::startSpringSystem(const std::vector<std::size_t>& members, bool xpbd)
{
    detail::SpringSolvers& solvers = *m_particleSystems.springSolvers;
    detail::SpringSolver& solver = xpbd ? solvers.xpbd : solvers.backwardEuler;
    solver.prepare(m_forces.objects, members, m_bodies.objects.size(), xpbd); // XPBD colours its constraints
    startSystem(members);
    CoupledScratch& s = m_particleSystems.scratch;
    s.mass.resize(members.size());
    detail::forEachIndex(members.size(), [&](std::size_t k) { s.mass[k] = m_bodies.masses[members[k]]; });
    // The fixed ends where the fixed bodies are (a program may have moved one between steps).
    std::vector<dvec3>& positions = solver.positions;
    positions.resize(m_bodies.objects.size());
    for (std::size_t i = 0; i < m_bodies.objects.size(); ++i)
        positions[i] = m_bodies.previous[i].pos;
    solver.springs.placeFixedEnds(positions);
    return solver;
}

void World::integrateBackwardEuler(const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted,
                                   double dt)
{
    detail::SpringSolver& solver = startSpringSystem(members, false);
    const std::size_t n = members.size();
    CoupledScratch& s = m_particleSystems.scratch;
    // Every force at the start of the step (the system's bodies are at it in m_bodies.trial already).
    sumSystemForces(members, wanted, {}, {}, nullptr);
    std::vector<dvec3>& start = solver.startForces;
    start.resize(n);
    // A member resting on the room is held on it (backward_euler.hpp): what arrives no faster than
    // the rule after the step takes for resting contact, twice what its acceleration gives in a
    // step, and lies no farther from it than that speed takes it in a step, nor than its own
    // radius (a point: than gravity's resting speed does). A member of a sheet stretched under a
    // crate is pulled at some 10^5 m/s^2, whose step reaches the floor a metre below: it was held
    // there in the air, still, while its springs stretched a quarter of a metre and more.
    const std::span<const Plane> planes(m_surfaces.planes);
    const double fall = 2.0 * glm::length(gravity()) * dt * dt;
    solver.heldOn.resize(n);
    solver.heldOnRoom.resize(n);
    detail::forEachIndex(n, [&](std::size_t k) {
        start[k] = m_forces.sums[members[k]];
        s.acc[k] = start[k] / s.mass[k];
        std::array<Plane, kMaxBallPlanes> room;
        const double radius = m_bodies.radii[members[k]], reach = restingReach(s.acc[k], dt);
        solver.heldOn[k] = restingOn(ballPlanes(planes, radius, room), s.x[k], s.v[k], reach,
                                    std::min(reach * dt, radius > 0.0 ? radius : fall));
        solver.heldOnRoom[k] = solver.heldOn[k] != dvec3(0.0);
    });
    holdOnBalls(members, solver.heldOn, dt);
    holdOnBodies(members, solver, dt);
    carryJoinedBodies(members, solver);
    solver.pointX.clear();
    solver.pointV.clear();
    solver.pointBody.clear();
    solver.jointSprings.clear();
    if (m_rigid.system) {
        const std::span<const dvec3> x(&s.x[0], n), v(&s.v[0], n);
        addJointPoints(*m_rigid.system, m_bodies.objects, members, x, v, s.mass, gravity(), dt, solver);
        linkPointsOfABody(x, dt, solver);
    }
    solveWithJointPoints(solver, std::span<dvec3>(&s.x[0], n), std::span<dvec3>(&s.v[0], n), dt);
    rubAndPushBearers(members, solver, dt);
    pushCarriedBodies(solver, dt);
    collideAndStore(members, dt, Integrator::ImplicitEuler);
}

void World::holdOnBodies(const std::vector<std::size_t>& members, detail::SpringSolver& solver, double dt) const
{
    // A member whose last contact with a rigid body lies within its radius of the body's surface
    // now, moving along its normal no faster than the room's resting contact allows, rests on it.
    const std::size_t n = members.size();
    solver.bearerOf.assign(n, detail::BackwardEuler::kNoBearer);
    solver.bearerArm.assign(n, dvec3(0.0));
    solver.heldFriction.assign(n, -1.0);
    solver.bearerBodies.clear();
    solver.bearers.clear();
    if (!m_rigid.system)
        return;
    const rigid::RigidSystem& system = *m_rigid.system;
    const CoupledScratch& s = m_particleSystems.scratch;
    const std::vector<std::size_t> supported = supportedBodies();
    for (const rigid::Contact& c : system.contacts()) {
        if (c.count == 0 || c.b >= system.size() || system.isPoint(c.a) == system.isPoint(c.b))
            continue;
        const bool pointIsA = system.isPoint(c.a);
        const std::size_t k = placeAmong(members, system.worldIndex(pointIsA ? c.a : c.b));
        const std::size_t world = system.worldIndex(pointIsA ? c.b : c.a);
        if (k == members.size() || solver.heldOn[k] != dvec3(0.0) ||
            std::binary_search(supported.begin(), supported.end(), world))
            continue;
        const auto& body = static_cast<const RigidBody&>(*m_bodies.objects[world]);
        const rigid::ContactPoint& deepest = deepestPoint(c);
        const dvec3 normal = pointIsA ? -deepest.normal : deepest.normal; // from the body to the member
        const dvec3 surface = body.getPos() + body.getOrientation() * (pointIsA ? deepest.anchorB : deepest.anchorA);
        const double radius = m_bodies.radii[members[k]], reach = restingReach(s.acc[k], dt);
        const dvec3 arm = s.x[k] - radius * normal - body.getPos();
        const dvec3 point = body.isFixed() ? dvec3(0.0) : body.getVel() + glm::cross(body.getAngularVelocity(), arm);
        if (glm::dot(normal, s.x[k] - surface) - radius > radius || std::abs(glm::dot(normal, s.v[k] - point)) > reach)
            continue;
        solver.heldOn[k] = normal;
        solver.heldFriction[k] = detail::combinedFriction(m_bodies.frictions[members[k]], body.getFriction());
        if (!body.isFixed()) {
            solver.bearerOf[k] = bearerFor(solver, world, dt);
            solver.bearerArm[k] = arm;
        }
    }
}

std::vector<std::size_t> World::supportedBodies() const
{
    // A body resting on the room or a fixed body is held up by them too, which the sheet's solve
    // does not see: its members are left to the contacts after the step, as before the hold. (Held
    // on it, a cloth over a box on the floor still moved at 1 to 8 cm/s after 6 s, against 0.4 mm/s.)
    std::vector<std::size_t> supported;
    const rigid::RigidSystem& system = *m_rigid.system;
    for (const rigid::Contact& c : system.contacts()) {
        if (c.count == 0 || system.isPoint(c.a) || (c.b < system.size() && system.isPoint(c.b)))
            continue;
        const bool onStatic = c.b >= system.size() || m_bodies.objects[system.worldIndex(c.b)]->isFixed();
        if (onStatic && deepestPoint(c).separation <= system.settings().linearSlop)
            supported.push_back(system.worldIndex(c.a));
    }
    std::sort(supported.begin(), supported.end());
    return supported;
}

std::uint32_t World::bearerFor(detail::SpringSolver& solver, std::size_t world, double dt) const
{
    const auto found = std::find(solver.bearerBodies.begin(), solver.bearerBodies.end(), world);
    if (found != solver.bearerBodies.end())
        return std::uint32_t(found - solver.bearerBodies.begin());
    // Its pushes come at the end of its free step, where they move it by its integrator's drift
    // of them (rigid::driftWeight): its point moves over the step as a body of its mass over that
    // share would (forward Euler's not at all, in this step). The solve starts from its velocity
    // now (a resting body's answer).
    const auto& body = static_cast<const RigidBody&>(*m_bodies.objects[world]);
    const double drift = rigid::driftWeight(body.getIntegrator());
    const dmat3 turn = glm::mat3_cast(body.getOrientation());
    const dmat3 inertia = turn * glm::inverse(body.getInverseInertiaBody()) * glm::transpose(turn);
    const dvec3 alone = body.getVel() + drift * gravity() * dt, spin = body.getAngularVelocity();
    const bool moves = drift > 0.0;
    solver.bearers.push_back({moves ? body.getMass() / drift : 1.0, moves ? inertia / drift : dmat3(1.0), alone, spin,
                              moves ? body.getVel() : alone, spin, moves});
    solver.bearerBodies.push_back(world);
    return std::uint32_t(solver.bearers.size() - 1);
}

void World::rubAndPushBearers(const std::vector<std::size_t>& members, detail::SpringSolver& solver, double dt)
{
    // The surface's friction, from its push, as the rule after the step gives a body it pushes:
    // on a body, against the member's slip over the body's point. A bearer takes the opposite
    // of what its members' pushes and friction gave them (summed in the members' order).
    CoupledScratch& s = m_particleSystems.scratch;
    solver.bearerImpulse.resize(members.size());
    detail::forEachIndex(members.size(), [&](std::size_t k) {
        const double push = solver.backwardEuler.push(k);
        const std::uint32_t b = solver.bearerOf[k];
        solver.bearerImpulse[k] = dvec3(0.0);
        if (!(push > 0.0))
            return;
        const dvec3 surface = b != detail::BackwardEuler::kNoBearer
                                  ? solver.bearers[b].velocity + glm::cross(solver.bearers[b].spin, solver.bearerArm[k])
                                  : dvec3(0.0);
        const double mu = solver.heldFriction[k] >= 0.0 ? solver.heldFriction[k] : m_bodies.frictions[members[k]];
        const dvec3 before = s.v[k];
        s.v[k] = surface + rubbedByPush(s.v[k] - surface, push * solver.heldOn[k], mu);
        // On the room, backward Euler's end velocity drives the step's whole slide: friction that
        // stops it stops the slide too (a rope's end lying on the floor crept 4.5 mm/s, still).
        if (solver.heldOnRoom[k] && b == detail::BackwardEuler::kNoBearer)
            s.x[k] += (s.v[k] - before) * dt;
        if (b != detail::BackwardEuler::kNoBearer)
            solver.bearerImpulse[k] = -solver.solveMass[k] * (s.v[k] - before + push * solver.heldOn[k]);
    });
    if (solver.bearers.empty())
        return;
    std::vector<std::pair<dvec3, dvec3>> given(solver.bearers.size(), {dvec3(0.0), dvec3(0.0)});
    for (std::size_t k = 0; k < members.size(); ++k)
        if (const std::uint32_t b = solver.bearerOf[k]; b != detail::BackwardEuler::kNoBearer) {
            given[b].first += solver.bearerImpulse[k];
            given[b].second += glm::cross(solver.bearerArm[k], solver.bearerImpulse[k]);
        }
    for (std::size_t b = 0; b < given.size(); ++b) {
        m_rigid.endPushes.push_back({solver.bearerBodies[b], given[b].first, given[b].second});
        m_rigid.system->keepAwake(m_bodies.rigidIndex[solver.bearerBodies[b]]);
    }
}

void World::carryJoinedBodies(const std::vector<std::size_t>& members, detail::SpringSolver& solver) const
{
    // A member joined at a point to a rigid body carries the body's mass at that point into the
    // solve, and its weight: the implicit springs then move the two as one, as the joint after the
    // step will. Alone, the member answered its springs as if free, and the joint then dragged it
    // back to a body a hundred times heavier: the springs felt at most the member's mass over dt
    // squared of the body, and a crate on a rope gained energy at 1/60 s. (A rod's and a spring
    // joint's body points are members of their own: addJointPoints.)
    const CoupledScratch& s = m_particleSystems.scratch;
    solver.solveMass.assign(s.mass.begin(), s.mass.end());
    solver.directionalMass.clear();
    solver.carried.clear();
    solver.links.clear();
    if (!m_rigid.system)
        return;
    const rigid::RigidSystem& system = *m_rigid.system;
    solver.links = linksInTheSolve(system, m_bodies.objects, members);
    for (const Link& l : solver.links) {
        const rigid::Joint& j = system.joints()[l.joint];
        const bool pointIsA = system.isPoint(j.a);
        const std::size_t k = l.member;
        const auto& body = static_cast<const RigidBody&>(*m_bodies.objects[l.body]);
        const dvec3 arm = body.getOrientation() * (pointIsA ? j.localB : j.localA);
        if (l.kind == Link::PinnedAlongRod) {
            // Its point does not move: the member answers as pinned along the rod, free across it.
            const dvec3 n = unitOrZero(s.x[k] + (pointIsA ? j.localA : j.localB) - (body.getPos() + arm));
            if (solver.directionalMass.empty())
                solver.directionalMass.assign(members.size(), dmat3(0.0));
            solver.directionalMass[k] += kPinnedMassRatio * s.mass[k] * glm::outerProduct(n, n);
        } else if (l.kind == Link::Carried && !l.moves) {
            // Its point does not move: the member answers as pinned there, a mass no spring moves
            // (and the body takes nothing: it carried a fixed table's share as speed it never had).
            solver.solveMass[k] += kPinnedMassRatio * s.mass[k];
        } else if (l.kind == Link::Carried) {
            // The least the body's point weighs in any direction (the trace bounds the largest
            // inverse inertia from above): the member never answers as heavier than the pair is.
            const dmat3 inverseInertia = body.getInverseInertiaBody();
            const double turn = inverseInertia[0][0] + inverseInertia[1][1] + inverseInertia[2][2];
            // A body with points in the solve too is shared among them and its carriers.
            const double carried = 1.0 / (1.0 / body.getMass() + glm::dot(arm, arm) * turn) / double(l.sharing);
            solver.solveMass[k] += carried;
            solver.startForces[k] += carried * gravity();
            solver.carried.push_back({k, l.body, carried, dmat3(1.0), arm, s.v[k]});
        }
    }
}

void World::pushCarriedBodies(detail::SpringSolver& solver, double dt)
{
    // What the springs gave the carried mass beyond its weight's fall is the body's, at the joint,
    // before its own step.
    const CoupledScratch& s = m_particleSystems.scratch;
    for (const auto& c : solver.carried) {
        const dvec3& after = c.member < s.v.size() ? s.v[c.member] : solver.pointV[c.member - s.v.size()];
        const dvec3 impulse = c.mass * (c.along * (after - c.before - gravity() * dt));
        pushBeforeItsStep(c.body, impulse, glm::cross(c.arm, impulse));
    }
}

void World::pushBeforeItsStep(std::size_t body, const dvec3& impulse, const dvec3& moment)
{
    auto& b = static_cast<RigidBody&>(*m_bodies.objects[body]);
    b.setVel(b.getVel() + impulse / b.getMass());
    b.setAngularMomentum(b.getAngularMomentum() + moment);
    m_rigid.system->keepAwake(m_bodies.rigidIndex[body]);
}

void World::holdOnBalls(const std::vector<std::size_t>& members, std::span<dvec3> heldOn, double dt) const
{
    // The last step's touching balls: a member not held on the room rests on the ball of a pair
    // that lies below it (against gravity), touching it and moving along their normal no faster
    // than it would rest on a surface (restingOn), and is held on it likewise.
    const detail::BallContacts& contacts = *m_particleSystems.ballContacts;
    const dvec3 g = gravity();
    if (contacts.pairs.empty() || !(glm::length(g) > 0.0))
        return;
    const dvec3 up = -g / glm::length(g);
    const CoupledScratch& s = m_particleSystems.scratch;
    for (const auto& [a, b] : contacts.pairs)
        for (const auto& [upper, lower] : {std::pair(contacts.bodies[a], contacts.bodies[b]),
                                           std::pair(contacts.bodies[b], contacts.bodies[a])}) {
            const std::size_t k = placeAmong(members, upper);
            if (k == members.size() || lower >= m_bodies.objects.size() || heldOn[k] != dvec3(0.0))
                continue; // (one of another system, a body the world no longer has, or one held)
            const std::size_t j = placeAmong(members, lower);
            const State below = j < members.size() ? State{s.x[j], s.v[j]} : m_bodies.previous[lower];
            const dvec3 d = s.x[k] - below.pos;
            const double distance = glm::length(d), reach = restingReach(s.acc[k], dt);
            if (!(distance > 0.0) || distance > kBallsHeldWithin * (m_bodies.radii[upper] + m_bodies.radii[lower]))
                continue;
            const dvec3 n = d / distance;
            if (glm::dot(n, up) >= kBallsHeldAbove && std::abs(glm::dot(n, s.v[k] - below.vel)) <= reach)
                heldOn[k] = n;
        }
}

detail::XpbdRigidContacts* World::startXpbdRigidContacts(const std::vector<std::size_t>& members,
                                                         detail::SpringSolver& solver, double dt)
{
    // The rigid bodies inside every substep too (xpbd_rigid_contacts.hpp), both ways, but for a
    // particle and the body a joint joins it to (unless the joint says they collide); and the
    // joints between them held there too (the joint solver after the step leaves their springs
    // alone).
    std::vector<std::pair<std::size_t, const RigidBody*>> rigid;
    for (std::size_t i = 0; i < m_bodies.objects.size(); ++i)
        if (isRigid(i))
            rigid.emplace_back(i, static_cast<const RigidBody*>(m_bodies.objects[i].get()));
    std::vector<detail::XpbdRigidContacts::Joint> joints;
    const rigid::RigidSystem& system = *m_rigid.system;
    for (const rigid::Joint& j : system.joints()) {
        if (j.b == rigid::kWorldBody || system.isPoint(j.a) == system.isPoint(j.b))
            continue;
        const bool pointFirst = system.isPoint(j.a);
        const auto [point, body] = pointFirst ? std::pair(j.a, j.b) : std::pair(j.b, j.a);
        joints.push_back({system.worldIndex(point), system.worldIndex(body), pointFirst ? j.localA : j.localB,
                          pointFirst ? j.localB : j.localA, j.type == JointType::Distance ? j.length : 0.0,
                          j.stiffness, j.damping, j.collide});
    }
    const CoupledScratch& s = m_particleSystems.scratch;
    const std::size_t n = members.size();
    detail::XpbdRigidContacts& bodies = solver.rigidContacts;
    bodies.begin(rigid,
                 {members, std::span<const dvec3>(&s.x[0], n), std::span<const dvec3>(&s.v[0], n), solver.radius,
                  s.mass, solver.friction, solver.restitution},
                 joints, dt);
    return bodies.empty() ? nullptr : &bodies;
}

void World::giveXpbdReactions(const detail::XpbdRigidContacts& bodies)
{
    // What the substeps gave the bodies starts their own step; pushed, they stay awake.
    for (const auto& r : bodies.reactions())
        pushBeforeItsStep(r.body, r.impulse, r.moment);
}

void World::integrateXpbd(const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted, double dt)
{
    detail::SpringSolver& solver = startSpringSystem(members, true);
    const std::size_t n = members.size();
    CoupledScratch& s = m_particleSystems.scratch;
    // Every force but the springs, which are the constraints, at each substep's start.
    const detail::Xpbd::External external = [&](std::span<const dvec3> x, std::span<const dvec3> v,
                                                std::span<dvec3> accel) {
        sumSystemForces(members, wanted, x, v, &solver.springs);
        detail::forEachIndex(n, [&](std::size_t k) { accel[k] = m_forces.sums[members[k]] / s.mass[k]; });
    };
    // The room inside every substep (xpbd.hpp), each member with its own radius, restitution and friction.
    solver.radius.resize(n);
    solver.restitution.resize(n);
    solver.friction.resize(n);
    detail::forEachIndex(n, [&](std::size_t k) {
        solver.radius[k] = m_bodies.radii[members[k]];
        solver.restitution[k] = m_bodies.cors[members[k]];
        solver.friction[k] = m_bodies.frictions[members[k]];
    });
    // Its members against each other inside every substep too (but for those its springs hold
    // near): the contacts after the step then find them apart.
    detail::SpringNeighbours& neighbours = *m_particleSystems.neighbours;
    auto near = [&, updated = false](std::size_t a, std::size_t b) mutable {
        if (!updated) // (only for a system with balls)
            neighbours.update(m_forces.objects, m_bodies.radii);
        updated = true;
        return neighbours.near(a, b);
    };
    const auto touching = touchingMembers(solver, std::span<const dvec3>(&s.x[0], n), std::span<const dvec3>(&s.v[0], n),
                                          members, near, dt);
    detail::Xpbd::Room room{m_surfaces.planes, solver.radius, solver.restitution, solver.friction, touching,
                            startXpbdRigidContacts(members, solver, dt)};
    solver.xpbd.step(solver.springs, s.mass, std::span<dvec3>(&s.x[0], n), std::span<dvec3>(&s.v[0], n), dt,
                     m_particleSystems.xpbdSubsteps, external, room);
    detail::forEachIndex(n, [&](std::size_t k) {
        m_bodies.bounces[members[k]] += std::uint64_t(solver.xpbd.bounces(k));
    });
    if (room.obstacles)
        giveXpbdReactions(solver.rigidContacts);
    // The step's mean acceleration: XPBD has no force at the start to keep.
    detail::forEachIndex(n, [&](std::size_t k) { s.acc[k] = (s.v[k] - m_bodies.previous[members[k]].vel) / dt; });
    collideAndStore(members, dt, Integrator::Xpbd);
}

void World::collideBalls(double dt)
{
    detail::BallContacts& contacts = *m_particleSystems.ballContacts;
    contacts.balls.clear();
    contacts.bodies.clear();
    contacts.pairs.clear(); // (read by the next step's holdOnBalls: none if fewer than two balls)
    std::vector<std::uint8_t>& sprung = contacts.sprung;
    sprung.assign(m_bodies.objects.size(), 0);
    for (const auto& [a, b] : m_forces.couplings)
        sprung[a] = sprung[b] = 1;
    for (std::size_t i = 0; i < m_bodies.objects.size(); ++i) {
        if (m_bodies.radii[i] == 0.0)
            continue;
        const Body& b = *m_bodies.objects[i];
        contacts.bodies.push_back(i);
        contacts.balls.push_back({.x = b.getPos(),
                                  .v = b.getVel(),
                                  .start = m_bodies.previous[i].pos,
                                  .inverseMass = b.isFixed() ? 0.0 : 1.0 / m_bodies.masses[i],
                                  .radius = m_bodies.radii[i],
                                  .cor = m_bodies.cors[i],
                                  .friction = m_bodies.frictions[i],
                                  .restingSpeed = glm::length(b.getAcc()) * dt,
                                  .metInSubsteps = b.getIntegrator() == Integrator::Xpbd,
                                  .sprung = sprung[i] != 0});
    }
    if (contacts.balls.size() < 2)
        return;
    // Particles of one rope or cloth collide too (a sheet falling in folds), except where its
    // springs hold them near each other.
    detail::SpringNeighbours& neighbours = *m_particleSystems.neighbours;
    neighbours.update(m_forces.objects, m_bodies.radii);
    // The nets' segments, by their balls' places in the list (the list is in the world's order).
    contacts.segments.clear();
    contacts.piecesGeneration = neighbours.generation();
    const auto ballOf = [&](std::size_t body) {
        return std::uint32_t(std::lower_bound(contacts.bodies.begin(), contacts.bodies.end(), body) - contacts.bodies.begin());
    };
    const auto isBall = [&](std::uint32_t k, std::size_t body) {
        return k < contacts.bodies.size() && contacts.bodies[k] == body;
    };
    for (const auto& [a, b] : neighbours.segments())
        if (const std::uint32_t ba = ballOf(a), bb = ballOf(b); isBall(ba, a) && isBall(bb, b))
            contacts.segments.emplace_back(ba, bb);
    contacts.triangles.clear();
    for (const auto& [a, b, c] : neighbours.triangles())
        if (const std::uint32_t ba = ballOf(a), bb = ballOf(b), bc = ballOf(c);
            isBall(ba, a) && isBall(bb, b) && isBall(bc, c))
            contacts.triangles.push_back({ba, bb, bc});
    constexpr int kSweeps = 8;
    contacts.solve(m_surfaces.planes, kSweeps, dt, [&](std::uint32_t a, std::uint32_t b) {
        return !neighbours.near(contacts.bodies[a], contacts.bodies[b]);
    });
    const auto bounced = [&](std::uint32_t ball) {
        if (!m_bodies.objects[contacts.bodies[ball]]->isFixed())
            ++m_bodies.bounces[contacts.bodies[ball]];
    };
    for (const auto& met : contacts.impacts.met())
        if (met.rebounded) {
            bounced(met.a);
            if (met.b != met.a) // (a ball on a piece: met.b is the ball again)
                bounced(met.b);
        }
    if (contacts.pairs.empty() && contacts.onNets.empty() && contacts.impacts.met().empty())
        return;
    for (std::size_t k = 0; k < contacts.pairs.size(); ++k)
        if (contacts.rebounded(k))
            for (const std::uint32_t ball : {contacts.pairs[k].first, contacts.pairs[k].second})
                if (!m_bodies.objects[contacts.bodies[ball]]->isFixed())
                    ++m_bodies.bounces[contacts.bodies[ball]];
    for (std::size_t k = 0; k < contacts.onNets.size(); ++k) {
        const detail::NetPoint& toucher = contacts.onNets[k].toucher;
        const std::size_t ball = contacts.bodies[toucher.ends[0]];
        if (toucher.count == 1 && contacts.reboundedOnNet(k) && !m_bodies.objects[ball]->isFixed())
            ++m_bodies.bounces[ball]; // (a ball's: a crossing of two segments bounces no ball of its own)
    }
    for (std::size_t k = 0; k < contacts.balls.size(); ++k)
        if (!m_bodies.objects[contacts.bodies[k]]->isFixed())
            m_bodies.objects[contacts.bodies[k]]->setState({contacts.balls[k].x, contacts.balls[k].v});
}

void World::collideGrains(Swarm& swarm, std::size_t slot, std::span<const PlaneT<float>> room, double restingSpeed,
                          double dt)
{
    const detail::GrainRule rule{swarm.radius(), swarm.restitution(), swarm.friction(), float(restingSpeed),
                                 float(dt)};
    constexpr int kSweeps = 8;
    detail::onCores(m_threads, [&] { m_particleSystems.grainContacts->solve(swarm, slot, room, rule, kSweeps); });
}

} // namespace pba
