#pragma once
// How `pba bench` times things: windows of a fixed number of steps, taken in turn by every
// subject of a measurement so that the machine's drifting speed slows them alike, and a run
// timed span by span as a program would step it.
#include <chrono>
#include <cstddef>
#include <functional>
#include <vector>

#include "pba/world.hpp"

namespace pba::app::bench {

using Clock = std::chrono::steady_clock;

/// The cores the rows call "all cores": what the machine reports, at least one.
int machineCores();

/// Seconds since `from`.
double seconds(Clock::time_point from);

/// Runs `step` until minTime has passed; how many times it ran.
long stepsIn(double minTime, const std::function<void()>& step);

/// Runs `step` `steps` times; the rate, in particle-steps per second (n particles a step).
double timedRate(std::size_t n, long steps, const std::function<void()>& step);

/// The median of a few rates.
double median(std::vector<double> rates);

/// The best of a few rates.
double best(const std::vector<double>& rates);

/// Times the subjects' windows in turn, round after round (measureSize says why): each first
/// takes as many steps as fill minTime, then every window restarts it and takes that many.
/// S has `step` and `restart` (callables), `steps` and `rates`.
template <class S>
void timeInTurn(std::vector<S>& subjects, std::size_t perStep, double minTime, int repeats)
{
    for (S& subject : subjects) {
        subject.step(); // warm caches and page in memory
        subject.steps = stepsIn(minTime, subject.step);
    }
    for (int r = 0; r < repeats; ++r)
        for (S& subject : subjects) {
            subject.restart();
            subject.rates.push_back(timedRate(perStep, subject.steps, subject.step));
        }
}

/// A world that a subject steps (at the swarm scenes' dt, 0.002, or another), and restarts from
/// where it began.
struct Restartable {
    std::function<void()> step, restart;
};

Restartable restartable(World world, double dt = 0.002);

/// A world stepped as a program steps it, `spans` spans of `spanSteps` steps, each timed: the
/// slowest span's steps per second and its index (from 0), and the seconds of the whole run.
struct SpanTimes {
    double slowest = 0.0, total = 0.0;
    int slowestSpan = 0;
};

SpanTimes timeSpans(World& world, double dt, int spans, int spanSteps);

} // namespace pba::app::bench
