#include "pba/frame_clock.hpp"

#include <algorithm>
#include <stdexcept>

#include "pba/clock.hpp"

#include "clock/clock_checks.hpp"

namespace pba {

using detail::requirePositiveTime;

std::string_view clockName(ClockKind kind)
{
    switch (kind) {
    case ClockKind::Fixed: return "fixed";
    case ClockKind::SemiFixed: return "semi-fixed";
    case ClockKind::Variable: return "variable";
    }
    return "fixed";
}

std::optional<ClockKind> clockFromName(std::string_view name)
{
    for (const ClockKind kind : kClockKinds)
        if (clockName(kind) == name)
            return kind;
    return std::nullopt;
}

std::vector<double> frameSteps(ClockKind kind, double dt, double frameTime, double maxFrameTime)
{
    requirePositiveTime(dt, "dt");
    requirePositiveTime(frameTime, "frame time");
    requirePositiveTime(maxFrameTime, "maximum frame time");
    if (kind == ClockKind::Fixed)
        throw std::invalid_argument("the fixed clock keeps an accumulator: FixedTimestepClock steps it");
    if (kind == ClockKind::Variable)
        return {frameTime};
    // Semi-fixed: Fiedler's `while (frameTime > 0) { step(min(frameTime, dt)); frameTime -= ...; }`.
    // A remainder below a billionth of dt is the sum's rounding, not time to step (as for the fixed clock).
    double left = std::min(frameTime, maxFrameTime);
    std::vector<double> steps;
    while (left > FixedTimestepClock::kRoundingTolerance * dt) {
        const double h = std::min(left, dt);
        steps.push_back(h);
        left -= h;
    }
    return steps;
}

} // namespace pba
