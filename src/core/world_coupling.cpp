// Which of a World's bodies forces couple into systems, integrated together, and which step
// alone: made again whenever a body's integrator or fixedness changes.
#include "pba/world.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace pba {

namespace {

/// For each non-empty list of body indices, a flag per body of the world: whether it is in the
/// list (the forces' wanted list of a system). An empty list gets no flags.
template <std::size_t N>
void markMembers(const std::array<std::vector<std::size_t>, N>& lists, std::size_t bodies,
                 std::array<std::vector<std::uint8_t>, N>& flags)
{
    for (std::size_t k = 0; k < N; ++k) {
        if (lists[k].empty())
            continue;
        flags[k].assign(bodies, 0);
        for (const std::size_t i : lists[k])
            flags[k][i] = 1;
    }
}

/// "forward-euler, ..., or splitting": the methods a rigid body may take.
std::string rigidIntegratorNames()
{
    std::string names;
    for (std::size_t k = 0; k < kRigidIntegrators.size(); ++k)
        names += fmt::format("{}{}", k == 0 ? "" : k + 1 == kRigidIntegrators.size() ? " or " : ", ",
                             integratorName(kRigidIntegrators[k]));
    return names;
}

} // namespace

const World::Coupling& World::couple()
{
    if (m_particleSystems.coupling.madeFrom != m_bodies.keys) // the keys read by storePreviousStates
        m_particleSystems.coupling = makeCoupling();
    return m_particleSystems.coupling;
}

World::Coupling World::makeCoupling() const
{
    Coupling coupling;
    std::vector<std::uint8_t> coupled(m_bodies.objects.size(), 0); // a moving body some force couples
    for (std::size_t k = 0; k < m_forces.couplings.size(); ++k) {
        const auto [a, b] = m_forces.couplings[k];
        const Body& first = *m_bodies.objects[a];
        const Body& second = *m_bodies.objects[b];
        for (const std::size_t end : {a, b})
            if (isRigid(end))
                throw std::invalid_argument(fmt::format(
                    "rigid body '{}' is joined to another body by a {}: forces between bodies act on particles only "
                    "(a rigid body's spring is anchored)",
                    m_bodies.objects[end]->getName(), m_forces.objects[m_forces.couplingForce[k]]->type()));
        // Pairs with a fixed end couple nothing between moving bodies, so they put no
        // condition on the integrators; a moving end is still integrated as coupled,
        // since its force needs the other end's state.
        if (!first.isFixed() && !second.isFixed() &&
            translationalMethod(first.getIntegrator()) != translationalMethod(second.getIntegrator()))
            throw std::invalid_argument(fmt::format(
                "bodies '{}' and '{}' are coupled by a {} but use different integrators ({} and {}): "
                "bodies coupled by forces must share one integrator",
                first.getName(), second.getName(), m_forces.objects[m_forces.couplingForce[k]]->type(),
                integratorName(first.getIntegrator()), integratorName(second.getIntegrator())));
        coupled[a] = first.isFixed() ? 0 : 1;
        coupled[b] = second.isFixed() ? 0 : 1;
    }
    coupling.madeFrom = m_bodies.keys;
    for (std::size_t i = 0; i < m_bodies.objects.size(); ++i) {
        const Integrator integrator = m_bodies.objects[i]->getIntegrator();
        if (isRigid(i) && isSpringSystemMethod(integrator) && !m_bodies.objects[i]->isFixed())
            throw std::invalid_argument(fmt::format(
                "rigid body '{}' takes {}, a method for particles joined by springs: a rigid body takes {}",
                m_bodies.objects[i]->getName(), integratorName(integrator), rigidIntegratorNames()));
        // A particle on implicit-euler or xpbd is stepped as a system even with no spring: its
        // step is the system's (a lone particle's system is itself).
        const bool system = isSpringSystemMethod(integrator) && !isRigid(i) && !m_bodies.objects[i]->isFixed();
        if (coupled[i] != 0 || system) {
            const auto k =
                std::find(kParticleIntegrators.begin(), kParticleIntegrators.end(), translationalMethod(integrator));
            coupling.systems[std::size_t(k - kParticleIntegrators.begin())].push_back(i);
        } else if (!isRigid(i)) { // the rigid system steps the rigid ones, fixed or moving
            coupling.independent.push_back(i);
        }
    }
    markMembers(coupling.systems, m_bodies.objects.size(), coupling.wanted);
    return coupling;
}

bool World::isCoupled(std::size_t i) const
{
    if (m_bodies.objects[i]->isFixed())
        return false;
    if (!isRigid(i) && isSpringSystemMethod(m_bodies.objects[i]->getIntegrator()))
        return true;
    return std::any_of(m_forces.couplings.begin(), m_forces.couplings.end(),
                       [i](const auto& p) { return p.first == i || p.second == i; });
}

bool World::hasCoupledBodies() const
{
    for (std::size_t i = 0; i < m_bodies.objects.size(); ++i) {
        const Body& b = *m_bodies.objects[i];
        if (!isRigid(i) && !b.isFixed() && isSpringSystemMethod(b.getIntegrator()))
            return true;
    }
    return std::any_of(m_forces.couplings.begin(), m_forces.couplings.end(), [this](const auto& p) {
        return !m_bodies.objects[p.first]->isFixed() || !m_bodies.objects[p.second]->isFixed();
    });
}

std::vector<std::size_t> World::coupledGroup(std::size_t i) const
{
    const auto& pairs = m_forces.couplings;
    std::vector<std::uint8_t> inGroup(m_bodies.objects.size(), 0);
    inGroup[i] = 1;
    // Grow the group until no pair of moving bodies adds to it: a few passes for a chain
    // listed in order, at worst one per body (a read-out, not part of the step).
    for (bool grew = !m_bodies.objects[i]->isFixed(); grew;) {
        grew = false;
        for (const auto& [a, b] : pairs) {
            if (m_bodies.objects[a]->isFixed() || m_bodies.objects[b]->isFixed() || inGroup[a] == inGroup[b])
                continue;
            inGroup[a] = inGroup[b] = 1;
            grew = true;
        }
    }
    std::vector<std::size_t> group;
    for (std::size_t k = 0; k < m_bodies.objects.size(); ++k)
        if (inGroup[k] != 0)
            group.push_back(k);
    return group;
}

} // namespace pba
