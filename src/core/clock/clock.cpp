#include "pba/clock.hpp"

#include <cmath>

#include "clock/clock_checks.hpp"

namespace pba {

using detail::requirePositiveSteps;
using detail::requirePositiveTime;

FixedTimestepClock::FixedTimestepClock(double dt, double maxFrameTime, int maxStepsPerFrame)
    : m_dt(dt), m_maxFrameTime(maxFrameTime), m_maxStepsPerFrame(maxStepsPerFrame)
{
    requirePositiveTime(dt, "dt");
    requirePositiveTime(maxFrameTime, "maximum frame time");
    requirePositiveSteps(maxStepsPerFrame);
}

void FixedTimestepClock::accumulate(double seconds)
{
    const double sum = m_accumulator + seconds;
    m_compensation += std::abs(m_accumulator) >= std::abs(seconds) ? (m_accumulator - sum) + seconds
                                                                     : (seconds - sum) + m_accumulator;
    m_accumulator = sum;
}

int FixedTimestepClock::advance(double frameTime)
{
    requirePositiveTime(frameTime, "frame time");
    if (frameTime > m_maxFrameTime) {
        m_dropped += frameTime - m_maxFrameTime;
        frameTime = m_maxFrameTime;
    }
    accumulate(frameTime);
    // Neither the frame times nor dt are exact in binary (1/60 s, 0.001 s): sixty frames of 1/60 s
    // hold a hair less than a thousand steps of 0.001 s even summed exactly. A step short of dt
    // by no more than that rounding, a billionth of dt, is taken; the compensated sum keeps the
    // rounding of any run far below it.
    const double step = m_dt * (1.0 - kRoundingTolerance);
    int steps = 0;
    while (accumulator() >= step && steps < m_maxStepsPerFrame) {
        accumulate(-m_dt);
        ++steps;
    }
    if (accumulator() >= step) { // the cap was hit: give up the whole steps that remain
        const double excess = std::floor(accumulator() / step) * m_dt;
        accumulate(-excess);
        m_dropped += excess;
    }
    if (accumulator() >= m_dt || accumulator() < 0.0) { // rounding at the boundary: keep alpha in [0, 1)
        m_accumulator = 0.0;
        m_compensation = 0.0;
    }
    m_totalSteps += static_cast<std::uint64_t>(steps);
    return steps;
}

void FixedTimestepClock::setDt(double dt)
{
    requirePositiveTime(dt, "dt");
    const double fraction = alpha();
    m_dt = dt;
    m_accumulator = fraction * dt;
    m_compensation = 0.0;
}

void FixedTimestepClock::setMaxFrameTime(double seconds)
{
    requirePositiveTime(seconds, "maximum frame time");
    m_maxFrameTime = seconds;
}

void FixedTimestepClock::setMaxStepsPerFrame(int steps)
{
    requirePositiveSteps(steps);
    m_maxStepsPerFrame = steps;
}

void FixedTimestepClock::reset()
{
    m_accumulator = 0.0;
    m_compensation = 0.0;
    m_dropped = 0.0;
    m_totalSteps = 0;
}

} // namespace pba
