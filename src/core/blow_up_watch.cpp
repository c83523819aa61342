#include "pba/blow_up_watch.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace pba {

namespace {

/// The share of the step's end force in a method's change of velocity over the step: none for
/// forward and semi-implicit Euler (v1 = v0 + a0 dt, the implicit gyroscopic step's translation
/// too), half for velocity Verlet, the splitting (whose translation is velocity Verlet), RK4 (its
/// stages weighed as the trapezoid would) and XPBD (its substeps'), all for backward Euler.
double endForceWeight(Integrator integrator)
{
    switch (integrator) {
    case Integrator::ForwardEuler:
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitGyroscopic: return 0.0;
    case Integrator::VelocityVerlet:
    case Integrator::Splitting:
    case Integrator::RK4:
    case Integrator::Xpbd: return 0.5;
    case Integrator::ImplicitEuler: return 1.0;
    }
    return 0.0;
}

} // namespace

BlowUpWatch::BlowUpWatch(const World& world) : m_active(true), m_start(world.totalEnergy()), m_time(world.time())
{
    for (std::size_t f = 0; f < world.forceCount(); ++f)
        m_sources = m_sources || world.force(f).addsEnergy();
    m_growth = std::isfinite(m_start);
    addSourceWork(world);
    m_startEnergies = world.energies();
    const double g = glm::length(world.gravity());
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        const Body& b = world.body(i);
        if (b.isFixed()) {
            m_fixed.emplace_back(i, b.getState());
            continue;
        }
        const double kinetic = world.kineticEnergy(i);
        m_scale += kinetic + std::abs(m_startEnergies[i] - kinetic) + b.getMass() * g * kLiftHeight;
    }
}

void BlowUpWatch::check(const World& world)
{
    if (!m_active)
        return;
    addSourceWork(world);
    // The total is finite when every body's energy is, and cheaper (each interaction once): only
    // when it is not is the culprit looked for.
    const double energy = world.totalEnergy();
    if (!std::isfinite(energy))
        throwNonFinite(world);
    if (m_growth && energy > energyBound() && !driven(world))
        throwGrowth(world, energy);
}

void BlowUpWatch::addSourceWork(const World& world)
{
    if (!m_sources)
        return;
    const std::size_t n = world.bodyCount();
    std::vector<std::pair<dvec3, dvec3>> velocities(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Body& b = world.body(i);
        velocities[i] = {b.getVel(),
                         world.isRigid(i) ? static_cast<const RigidBody&>(b).getAngularVelocity() : dvec3(0.0)};
    }
    std::vector<Wrench> wrenches = world.sourceWrenches();
    const double dt = world.time() - m_time;
    m_bodyWork.resize(n, 0.0);
    for (std::size_t i = 0; i < n && i < m_wrenches.size(); ++i) {
        // The force the body's method moved it with over the step, against its mean velocity.
        const double w = endForceWeight(world.body(i).getIntegrator());
        const Wrench& a = m_wrenches[i];
        const Wrench& b = wrenches[i];
        const double work = 0.5 * dt *
                            (glm::dot((1.0 - w) * a.force + w * b.force, m_velocities[i].first + velocities[i].first) +
                             glm::dot((1.0 - w) * a.torque + w * b.torque, m_velocities[i].second + velocities[i].second));
        m_bodyWork[i] += work;
        m_work += work;
    }
    m_wrenches = std::move(wrenches);
    m_velocities = std::move(velocities);
    m_time = world.time();
}

std::vector<double> BlowUpWatch::energiesWithoutSourceWork(const World& world) const
{
    std::vector<double> energies = world.energies();
    for (std::size_t i = 0; i < energies.size() && i < m_bodyWork.size(); ++i)
        energies[i] -= m_bodyWork[i];
    return energies;
}

bool BlowUpWatch::driven(const World& world) const
{
    return std::any_of(m_fixed.begin(), m_fixed.end(), [&](const auto& fixed) {
        const State now = world.body(fixed.first).getState();
        return now.pos != fixed.second.pos || now.vel != fixed.second.vel;
    });
}

void BlowUpWatch::throwNonFinite(const World& world) const
{
    const std::vector<double> energies = world.energies();
    std::size_t bad = 0; // the first body whose energy is not finite; with none (a sum that
    for (std::size_t i = 0; i < energies.size(); ++i) { // overflows), the largest term
        if (!std::isfinite(energies[i])) {
            bad = i;
            break;
        }
        if (std::abs(energies[i]) > std::abs(energies[bad]))
            bad = i;
    }
    throw NonFiniteStateError(world.bodyCount() > 0 ? world.body(bad).getName() : "", world.stepCount(), world.time(),
                              "energy");
}

void BlowUpWatch::throwGrowth(const World& world, double energy) const
{
    const std::vector<double> energies = world.energies();
    std::size_t most = 0;
    for (std::size_t i = 0; i < energies.size() && i < m_startEnergies.size(); ++i)
        if (energies[i] - m_startEnergies[i] > energies[most] - m_startEnergies[most])
            most = i;
    const std::string name = world.bodyCount() > 0 ? world.body(most).getName() : "";
    const std::string reason =
        m_sources ? fmt::format("the energy rose from {:.4g} J to {:.4g} J, more than {:g} times its energy scale "
                                "({:.4g} J) above its start and the {:.4g} J of work its energy sources did",
                                m_start, energy, kEnergyGrowthLimit, m_scale, m_work)
                  : fmt::format("the energy of a system with no energy source rose from {:.4g} J to {:.4g} J, more "
                                "than {:g} times its energy scale ({:.4g} J) above its start",
                                m_start, energy, kEnergyGrowthLimit, m_scale);
    throw BlowUpError(name, world.stepCount(), world.time(), fmt::format("{}, body '{}' gaining the most", reason, name));
}

} // namespace pba
