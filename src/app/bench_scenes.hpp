#pragma once
// `pba bench`'s scene rows, each stepped as a program steps it: a 128 x 128 cloth (springs), piles
// of 1,000 and 10,000 dice (rigid bodies with contacts), and fountain-1m through its whole duration.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "pba/integrator.hpp"

namespace pba::app::bench {

/// The cloth row's side: 128 x 128 particles, 97,026 springs.
constexpr int kClothSide = 128;

/// A cloth row: its method and dt, its physics steps per second (best window and median), and
/// what a step costs: semi-implicit Euler evaluates each spring once a step, implicit-euler
/// solves (its conjugate-gradient iterations in the last step of the last window), xpbd projects
/// each spring once a substep.
struct ClothRow {
    Integrator integrator = Integrator::SemiImplicitEuler;
    double dt = 0.0;
    int threads = 1;
    std::size_t particles = 0, springs = 0;
    double stepsPerSecond = 0.0, medianStepsPerSecond = 0.0;
    int iterations = 0; ///< implicit-euler's
    int substeps = 0;   ///< xpbd's
};

/// The cloth methods: semi-implicit Euler at its own dt, 0.002 (omega dt about 0.7 on this sheet,
/// a third of its limit), and the two that step springs implicitly at a frame's dt, 1/60 s
/// (real time with one step a frame).
struct ClothMethod {
    Integrator integrator;
    double dt;
};
inline constexpr std::array<ClothMethod, 3> kClothMethods{ClothMethod{Integrator::SemiImplicitEuler, 0.002},
                                                          ClothMethod{Integrator::ImplicitEuler, 1.0 / 60.0},
                                                          ClothMethod{Integrator::Xpbd, 1.0 / 60.0}};

/// The cloth with each method on 1 thread and on all cores, their windows taken in turn (as
/// measureSize's), each window the same work: from the scene's first state (the sheet falling
/// flat toward the jet), as many steps as filled a first window.
std::vector<ClothRow> measureCloth(double minTime, int repeats, int cores);

/// The pile rows' dice counts: manyDice's 10 cm boxes.
constexpr std::array<std::size_t, 2> kPileDice{1000, 10000};

/// A run timed span by span: physics steps per second in its slowest span (a program must keep
/// up with it) and over the whole run.
struct SpanRun {
    int threads = 1;
    double stepsPerSecond = 0.0, overallStepsPerSecond = 0.0;
    int spans = 0, spanSteps = 0;
    double slowestFrom = 0.0; ///< the simulated time the slowest span starts at, s
};

/// A pile row: its dice and its run.
struct PileRun {
    std::size_t dice = 0;
    SpanRun run;
};

/// A pile row: `dice` dice thrown into the dice scene's room (manyDice), semi-implicit Euler with
/// contacts on all cores, stepped as a program would from the throw through their landing
/// (bounces, slides, new contacts every step: the solver's hardest time) to rest, 4 s timed half
/// a simulated second at a time. (`quick`: two spans of 10 steps, in flight.)
PileRun runPile(std::size_t dice, bool quick, int cores);

/// fountain-1m as a program runs it: the run, its swarm's size and integrator.
struct SceneRun {
    SpanRun run;
    std::size_t n = 0;
    std::string integrator;
};

/// fountain-1m as a program runs it: a million particles, all cores, steps of the scene's dt
/// over its whole duration, timed a simulated second at a time (`quick`: two spans of 4 steps);
/// `cores`, what the row reports as its threads.
SceneRun runScene(bool quick, int cores);

} // namespace pba::app::bench
