#include "pba/blow_up_watch.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "parallel.hpp"

namespace pba {

namespace {

/// How a method weighs the forces of a step's start, middle and end in its change of velocity
/// over the step: forward and semi-implicit Euler (the implicit gyroscopic step's translation
/// too) take the start's, velocity Verlet, the splitting (whose translation is velocity Verlet)
/// and XPBD (its substeps') the mean of the start's and the end's, RK4 Simpson's rule, backward
/// Euler the end's. An approximation of stageWeights (integrator.hpp), which weighs the stages
/// where the method took them: it serves only the bodies whose flight is not booked (rigid
/// bodies, implicit Euler and XPBD systems).
struct StepWeights {
    double start, middle, end;
};

StepWeights stepWeights(Integrator integrator)
{
    switch (integrator) {
    case Integrator::ForwardEuler:
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitGyroscopic: return {1.0, 0.0, 0.0};
    case Integrator::VelocityVerlet:
    case Integrator::Splitting:
    case Integrator::Xpbd: return {0.5, 0.0, 0.5};
    case Integrator::RK4: return {1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0};
    case Integrator::ImplicitEuler: return {0.0, 0.0, 1.0};
    }
    return {1.0, 0.0, 0.0};
}

} // namespace

BlowUpWatch::BlowUpWatch(const World& world) : m_active(true), m_start(world.totalEnergy()), m_time(world.time())
{
    m_sources = world.hasEnergySources();
    m_growth = std::isfinite(m_start);
    m_lastHeld = m_start;
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
    if (const double rise = energy - m_work - m_lastHeld; rise > m_largestRise) {
        m_largestRise = rise;
        m_largestRiseAt = world.time();
    }
    m_lastHeld = energy - m_work;
    if (m_growth && energy > energyBound() && !driven(world))
        throwGrowth(world, energy);
}

void BlowUpWatch::addSourceWork(const World& world)
{
    if (!m_sources)
        return;
    // Each body read once, on all cores (a cloth of 16,384 members is watched after every step).
    const std::size_t n = world.bodyCount();
    std::vector<State> states(n);
    std::vector<dvec3> spins(n, dvec3(0.0));
    std::vector<StepWeights> weights(n);
    detail::forEachIndex(n, [&](std::size_t i) {
        const Body& body = world.body(i);
        states[i] = body.getState();
        weights[i] = stepWeights(body.getIntegrator());
        if (world.isRigid(i))
            spins[i] = static_cast<const RigidBody&>(body).getAngularVelocity();
    });
    const bool started = m_states.size() == n;
    // A body whose flight its integration booked (World::lastStepSourceWork) is exact. The rule
    // below weighs the sources' wrenches for every other moving body, evaluated only if there is
    // one (and at the start, for a first step that does not book them all).
    const std::span<const double> booked = world.lastStepSourceWork();
    const auto isBooked = [&](std::size_t i) { return started && i < booked.size() && !std::isnan(booked[i]); };
    bool weigh = !started;
    for (std::size_t i = 0; i < n && !weigh; ++i)
        weigh = !world.body(i).isFixed() && !isBooked(i);
    std::vector<Wrench> wrenches, halfway;
    if (weigh) {
        wrenches = world.sourceWrenches(states);
        if (started && m_wrenches.size() != n) // (the last step's were all booked)
            m_wrenches = world.sourceWrenches(m_states);
        // The middle of the step, where a method's stages look (RK4's), as the mean of its ends.
        if (started && std::any_of(weights.begin(), weights.end(), [](const StepWeights& w) { return w.middle != 0.0; })) {
            std::vector<State> mean(n);
            for (std::size_t i = 0; i < n; ++i)
                mean[i] = State{0.5 * (m_states[i].pos + states[i].pos), 0.5 * (m_states[i].vel + states[i].vel)};
            halfway = world.sourceWrenches(mean);
        }
    }
    const double dt = world.time() - m_time;
    std::vector<double> work(n, 0.0);
    detail::forEachIndex(started ? n : 0, [&](std::size_t i) {
        if (isBooked(i)) {
            work[i] = booked[i];
            return;
        }
        if (!weigh) // (a fixed body: it does not move)
            return;
        // The force the body's method moved it with over the step, against its mean velocity.
        const StepWeights w = weights[i];
        const Wrench mid = halfway.empty() ? Wrench{} : halfway[i];
        const dvec3 force = w.start * m_wrenches[i].force + w.middle * mid.force + w.end * wrenches[i].force;
        const dvec3 torque = w.start * m_wrenches[i].torque + w.middle * mid.torque + w.end * wrenches[i].torque;
        work[i] = 0.5 * dt * (glm::dot(force, m_states[i].vel + states[i].vel) + glm::dot(torque, m_spins[i] + spins[i]));
    });
    m_bodyWork.resize(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) { // (in the bodies' order: the same sum on any number of threads)
        m_bodyWork[i] += work[i];
        m_work += work[i];
    }
    m_wrenches = std::move(wrenches);
    m_states = std::move(states);
    m_spins = std::move(spins);
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
