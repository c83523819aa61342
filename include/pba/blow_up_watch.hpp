#pragma once
// A run can blow up without any state that World::step would refuse. Inside a closed room the
// walls keep a spring system's exploding positions finite, so a rope whose stiffness is 1e300, or
// the built-in rope at ten times its dt, runs to the end with its energy up a thousandfold or
// more. The step sees one step at a time; this watch compares the run with its start, and every
// command that runs a scene asks it after each step (sim, render, view, compare).
#include <cstddef>
#include <utility>
#include <vector>

#include "pba/state.hpp"
#include "pba/world.hpp"

namespace pba {

/// Watches a run for the blow-ups a single step cannot see.
///  - An energy that is not finite while the states are (1/2 k x^2 with x ~ 1e155): a
///    NonFiniteStateError naming the first such body, quantity "energy".
///  - Energy gained with nothing to feed it. The bodies' total energy can rise only by the work
///    of the energy sources (the forces that addsEnergy, such as the blow dryer), but for its
///    integrator's error: forward Euler gains half as much again on the integrators scene, and a
///    stable method near its stability limit swings further. One that rises more than
///    kEnergyGrowthLimit times the energy scale above its start and that work has left the
///    physics behind: a BlowUpError naming the body that gained the most. The sources' work over
///    a step, on a particle that moves alone or in a system of an explicit method, is exact:
///    each stretch of its flight was booked as its method took it (World::lastStepSourceWork),
///    so bounces within the step and a force that jumps within it are counted as they happened.
///    On any other body (rigid, of an implicit-euler or xpbd system) it is their wrench
///    (World::sourceWrenches) as the body's integrator weighs the step's start, middle and end,
///    against the mean of the step's start and end velocities (exact for forward and
///    semi-implicit Euler; for RK4, whose stages are its own, the middle is the mean of the start
///    and end states). Check after every step. A fixed body that the program has moved drives
///    the system with work no force accounts for: then energy growth is not checked.
/// The energy scale is the moving bodies' kinetic energy at the start plus the size of each one's
/// potential energy, plus what lifting each by kLiftHeight in the world's gravity takes (so that
/// a world starting at rest where its potential energy is zero, or with a start energy near zero
/// or negative, still has a scale). Swarms are not counted (their states are checked by the step).
class BlowUpWatch {
public:
    /// How many energy scales above its start and its sources' work the energy of a system may
    /// rise. Ordinary scenes at their own dt rise less than two (the largest: forward Euler on
    /// the spring, 1.7); a rope whose spring dampers are 1e300 peaks at 380 before its particles
    /// fold into a heap, and a spring above its stability limit passes 100 within a few steps.
    static constexpr double kEnergyGrowthLimit = 100.0;
    /// The height, in metres, each moving body's share of the energy scale is lifted by.
    static constexpr double kLiftHeight = 1.0;

    /// A watch of nothing: check() never throws.
    BlowUpWatch() = default;
    /// Watches the run of `world` from its current state (its start): its total energy, the
    /// energy scale, and whether the world has an energy source among its forces (forces added
    /// later are not seen: watch the world as it will run).
    explicit BlowUpWatch(const World& world);

    /// After each step of the world: adds the sources' work over the step, then throws
    /// NonFiniteStateError or BlowUpError (see the class), at the world's step count and time,
    /// if the run has blown up.
    void check(const World& world);

    /// Whether the energy-growth rule applies: the start's energy is finite.
    bool watchesGrowth() const { return m_growth; }
    /// Whether a force of the world may add energy, so that its work is summed.
    bool hasSources() const { return m_sources; }
    double startEnergy() const { return m_start; }
    double energyScale() const { return m_scale; }
    /// The work the energy sources have done on the bodies since the start, as of the last check.
    double sourceWork() const { return m_work; }
    /// Every body's energy (World::energies) less the work the sources did on it: what the
    /// integration, the contacts and the forces that keep energy made of the start's.
    std::vector<double> energiesWithoutSourceWork(const World& world) const;
    /// The largest rise, from one check to the next, of the energy less the sources' work (0 if
    /// it never rose), and the time of the check that saw it: what "its energy never grows from
    /// one step to the next" claims.
    double largestStepRise() const { return m_largestRise; }
    double largestStepRiseAt() const { return m_largestRiseAt; }
    /// The total energy above which the run has blown up: start + sources' work +
    /// kEnergyGrowthLimit * scale.
    double energyBound() const { return m_start + m_work + kEnergyGrowthLimit * m_scale; }

private:
    bool driven(const World& world) const;
    void addSourceWork(const World& world);
    [[noreturn]] void throwNonFinite(const World& world) const;
    [[noreturn]] void throwGrowth(const World& world, double energy) const;

    bool m_active = false;
    bool m_growth = false;
    bool m_sources = false;
    double m_start = 0.0;
    double m_scale = 0.0;
    double m_work = 0.0;
    double m_lastHeld = 0.0; ///< at the last check: the energy less the sources' work
    double m_largestRise = 0.0, m_largestRiseAt = 0.0;
    std::vector<double> m_bodyWork; ///< m_work body by body
    /// At the last check (or the start): the sources' wrench on each body, each body's state
    /// and angular velocity, and the world's time.
    std::vector<Wrench> m_wrenches;
    std::vector<State> m_states;
    std::vector<dvec3> m_spins;
    double m_time = 0.0;
    std::vector<double> m_startEnergies; ///< each body's, to name the one that gained the most
    /// The fixed bodies and their start states: one the program has moved drives the system.
    std::vector<std::pair<std::size_t, State>> m_fixed;
};

} // namespace pba
