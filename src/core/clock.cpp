#include "pba/clock.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace pba {

namespace {
void requirePositive(double value, const char* what)
{
    if (!std::isfinite(value) || value <= 0.0)
        throw std::invalid_argument(fmt::format("{} must be finite and positive, got {}", what, value));
}
} // namespace

FixedTimestepClock::FixedTimestepClock(double dt, double maxFrameTime, int maxStepsPerFrame)
    : m_dt(dt), m_maxFrameTime(maxFrameTime), m_maxStepsPerFrame(maxStepsPerFrame)
{
    requirePositive(dt, "dt");
    requirePositive(maxFrameTime, "maximum frame time");
    if (maxStepsPerFrame <= 0)
        throw std::invalid_argument(fmt::format("maximum steps per frame must be positive, got {}", maxStepsPerFrame));
}

int FixedTimestepClock::advance(double frameTime)
{
    requirePositive(frameTime, "frame time");
    if (frameTime > m_maxFrameTime) {
        m_dropped += frameTime - m_maxFrameTime;
        frameTime = m_maxFrameTime;
    }
    m_accumulator += frameTime;
    int steps = 0;
    while (m_accumulator >= m_dt && steps < m_maxStepsPerFrame) {
        m_accumulator -= m_dt;
        ++steps;
    }
    if (m_accumulator >= m_dt) { // the cap was hit: give up the whole steps that remain
        const double excess = std::floor(m_accumulator / m_dt) * m_dt;
        m_accumulator -= excess;
        m_dropped += excess;
        if (m_accumulator >= m_dt || m_accumulator < 0.0)
            m_accumulator = 0.0; // rounding at the boundary: keep alpha in [0, 1)
    }
    m_totalSteps += static_cast<std::uint64_t>(steps);
    return steps;
}

void FixedTimestepClock::setDt(double dt)
{
    requirePositive(dt, "dt");
    const double fraction = alpha();
    m_dt = dt;
    m_accumulator = fraction * dt;
}

void FixedTimestepClock::setMaxFrameTime(double seconds)
{
    requirePositive(seconds, "maximum frame time");
    m_maxFrameTime = seconds;
}

void FixedTimestepClock::setMaxStepsPerFrame(int steps)
{
    if (steps <= 0)
        throw std::invalid_argument(fmt::format("maximum steps per frame must be positive, got {}", steps));
    m_maxStepsPerFrame = steps;
}

void FixedTimestepClock::reset()
{
    m_accumulator = 0.0;
    m_dropped = 0.0;
    m_totalSteps = 0;
}

} // namespace pba
