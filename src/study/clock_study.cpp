#include "clock_study.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "pba/blow_up_watch.hpp"
#include "pba/clock.hpp"

namespace pba::study {

namespace {

/// The wall-clock times the frames end at: k / rate, and past the hitch kHitchAt + kHitchSeconds
/// + k / rate. Each is its own quotient, so a shared frame's time is the same at every rate.
std::vector<double> frameEnds(int rate, bool hitch, double duration)
{
    std::vector<double> ends;
    const double r = rate;
    for (long k = 1;; ++k) {
        const double t = double(k) / r;
        if (hitch && t > kHitchAt + 1e-12)
            break;
        if (t > duration + 1e-12)
            return ends;
        ends.push_back(t);
    }
    for (long k = 0;; ++k) {
        const double t = kHitchAt + kHitchSeconds + double(k) / r;
        if (t > duration + 1e-12)
            return ends;
        ends.push_back(t);
    }
}

bool isWhole(double x) { return std::abs(x - std::round(x)) < 1e-6; }

/// Whether wall-clock time t is a shared frame: a whole number of kClockSampleSeconds, or past
/// the hitch a whole number of them after it ends. Those on a step of dt count too: the fixed
/// clock takes a step that its sum of frame times misses by rounding alone.
bool isSharedFrame(double t, bool hitch)
{
    const double from = hitch && t > kHitchAt + 1e-12 ? kHitchAt + kHitchSeconds : 0.0;
    return isWhole((t - from) / kClockSampleSeconds);
}

std::vector<dvec3> movingPositions(const World& world)
{
    std::vector<dvec3> out;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (!world.body(i).isFixed())
            out.push_back(world.body(i).getPos());
    return out;
}

ClockRun runOne(const ClockConfig& config, ClockKind clock, int rate, bool hitch)
{
    ClockRun run{clock, rate, hitch, 0, config.dt, config.dt, {}, {}, std::numeric_limits<double>::quiet_NaN(), {}};
    World world = config.scene.world;
    BlowUpWatch watch(world);
    FixedTimestepClock fixed(config.dt);
    double last = 0.0;
    run.shortestStep = std::numeric_limits<double>::infinity();
    run.longestStep = 0.0;
    const auto step = [&](double h) { // the step is counted before it runs: the one that blows up too
        ++run.steps;
        run.shortestStep = std::min(run.shortestStep, h);
        run.longestStep = std::max(run.longestStep, h);
        world.step(h);
        watch.check(world);
    };
    try {
        for (const double end : frameEnds(rate, hitch, config.duration)) {
            const double frame = end - last;
            last = end;
            if (clock == ClockKind::Fixed)
                for (int n = fixed.advance(frame); n > 0; --n)
                    step(config.dt);
            else
                for (const double h : frameSteps(clock, config.dt, frame, FixedTimestepClock::kDefaultMaxFrameTime))
                    step(h);
            if (isSharedFrame(end, hitch)) {
                run.t.push_back(end);
                run.position.push_back(movingPositions(world));
            }
        }
    } catch (const BlowUpError& e) {
        run.blewUpAt = last;
        run.blowUp = e.what();
    }
    if (run.steps == 0)
        run.shortestStep = 0.0;
    return run;
}

ClockDrift driftOf(const ClockRun& run, const ClockRun& reference)
{
    ClockDrift d{run.clock, run.rate, run.hitch, {}, {}, 0.0, true};
    const std::size_t n = std::min(run.t.size(), reference.t.size());
    for (std::size_t s = 0; s < n; ++s) {
        double largest = 0.0;
        for (std::size_t b = 0; b < run.position[s].size(); ++b) {
            largest = std::max(largest, glm::length(run.position[s][b] - reference.position[s][b]));
            d.identical = d.identical && run.position[s][b] == reference.position[s][b];
        }
        d.t.push_back(run.t[s]);
        d.distance.push_back(largest);
        d.maxDistance = std::max(d.maxDistance, largest);
    }
    if (!std::isnan(run.blewUpAt) || !std::isnan(reference.blewUpAt)) {
        d.maxDistance = std::numeric_limits<double>::quiet_NaN();
        d.identical = false;
    }
    return d;
}

} // namespace

std::vector<double> frameTimes(int rate, bool hitch, double duration)
{
    std::vector<double> times;
    double last = 0.0;
    for (const double end : frameEnds(rate, hitch, duration)) {
        times.push_back(end - last);
        last = end;
    }
    return times;
}

ClockResult runClockStudy(const ClockConfig& config)
{
    if (!(config.dt > 0.0) || !std::isfinite(config.dt))
        throw std::invalid_argument(fmt::format("dt must be finite and positive, got {}", config.dt));
    if (!(config.duration >= kClockMinDuration))
        throw std::invalid_argument(fmt::format("the clocks study runs at least {:g} s (a hitch at {:g} s and a second "
                                                "after it), got {:g} s",
                                                kClockMinDuration, kHitchAt, config.duration));
    ClockResult result;
    for (const ClockKind clock : kClockKinds)
        for (const bool hitch : {false, true}) {
            const std::size_t first = result.runs.size();
            for (const int rate : kClockRates)
                result.runs.push_back(runOne(config, clock, rate, hitch));
            const auto reference = std::find_if(result.runs.begin() + long(first), result.runs.end(),
                                                 [](const ClockRun& r) { return r.rate == kClockReferenceRate; });
            for (auto r = result.runs.begin() + long(first); r != result.runs.end(); ++r)
                if (r->rate != kClockReferenceRate)
                    result.drifts.push_back(driftOf(*r, *reference));
        }
    return result;
}

} // namespace pba::study
