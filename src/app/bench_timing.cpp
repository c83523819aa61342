#include "bench_timing.hpp"

#include <algorithm>
#include <limits>
#include <memory>
#include <thread>

namespace pba::app::bench {

int machineCores() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

double seconds(Clock::time_point from) { return std::chrono::duration<double>(Clock::now() - from).count(); }

long stepsIn(double minTime, const std::function<void()>& step)
{
    const auto start = Clock::now();
    long steps = 0;
    do {
        step();
        ++steps;
    } while (seconds(start) < minTime);
    return steps;
}

double timedRate(std::size_t n, long steps, const std::function<void()>& step)
{
    const auto start = Clock::now();
    for (long k = 0; k < steps; ++k)
        step();
    return double(n) * double(steps) / seconds(start);
}

double median(std::vector<double> rates)
{
    std::sort(rates.begin(), rates.end());
    return rates[rates.size() / 2];
}

double best(const std::vector<double>& rates) { return *std::max_element(rates.begin(), rates.end()); }

Restartable restartable(World world, double dt)
{
    auto first = std::make_shared<const World>(std::move(world));
    auto current = std::make_shared<World>(*first);
    return {[current, dt] { current->step(dt); }, [current, first] { *current = *first; }};
}

SpanTimes timeSpans(World& world, double dt, int spans, int spanSteps)
{
    SpanTimes t{std::numeric_limits<double>::infinity(), 0.0, 0};
    for (int span = 0; span < spans; ++span) {
        const auto start = Clock::now();
        for (int k = 0; k < spanSteps; ++k)
            world.step(dt);
        const double elapsed = seconds(start);
        if (spanSteps / elapsed < t.slowest) {
            t.slowest = spanSteps / elapsed;
            t.slowestSpan = span;
        }
        t.total += elapsed;
    }
    return t;
}

} // namespace pba::app::bench
