#pragma once
// The clocks' checks of what they are given, shared by FixedTimestepClock and frameSteps so that
// both refuse a bad time with the same words.
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace pba::detail {

/// A time (dt, a frame time, its cap) must be finite and positive; std::invalid_argument naming it.
inline void requirePositiveTime(double seconds, const char* what)
{
    if (!std::isfinite(seconds) || seconds <= 0.0)
        throw std::invalid_argument(fmt::format("{} must be finite and positive, got {}", what, seconds));
}

/// The steps a frame may take must be positive.
inline void requirePositiveSteps(int steps)
{
    if (steps <= 0)
        throw std::invalid_argument(fmt::format("maximum steps per frame must be positive, got {}", steps));
}

} // namespace pba::detail
