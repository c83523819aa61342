// A World's phases for the systems whose springs are stepped implicitly: backward Euler
// (implicit-euler) and XPBD (xpbd). Each takes the system's start state, steps it with its solver
// (src/core/backward_euler.cpp, xpbd.cpp) and hands the end states to collideAndStore, as
// integrateCoupled does for the explicit methods.
#include "pba/world.hpp"

#include "parallel.hpp"
#include "spring_solvers.hpp"

namespace pba {

detail::SpringSolver& World::startSpringSystem(const std::vector<std::size_t>& members, bool xpbd)
{
    detail::SpringSolver& solver = xpbd ? m_particleSystems.springSolvers->xpbd : m_particleSystems.springSolvers->backwardEuler;
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
    detail::forEachIndex(n, [&](std::size_t k) {
        start[k] = m_forces.sums[members[k]];
        s.acc[k] = start[k] / s.mass[k];
    });
    solver.backwardEuler.step(solver.springs, s.mass, std::span<dvec3>(&s.x[0], n), std::span<dvec3>(&s.v[0], n),
                              start, dt);
    collideAndStore(members);
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
    solver.xpbd.step(solver.springs, s.mass, std::span<dvec3>(&s.x[0], n), std::span<dvec3>(&s.v[0], n), dt,
                     m_particleSystems.xpbdSubsteps, external);
    // The step's mean acceleration: XPBD has no force at the start to keep.
    detail::forEachIndex(n, [&](std::size_t k) { s.acc[k] = (s.v[k] - m_bodies.previous[members[k]].vel) / dt; });
    collideAndStore(members);
}

} // namespace pba
