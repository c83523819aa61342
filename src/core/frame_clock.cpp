#include "pba/frame_clock.hpp"

#include <algorithm>
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
    requirePositive(dt, "dt");
    requirePositive(frameTime, "frame time");
    requirePositive(maxFrameTime, "maximum frame time");
    if (kind == ClockKind::Fixed)
        throw std::invalid_argument("the fixed clock keeps an accumulator: FixedTimestepClock steps it");
    if (kind == ClockKind::Variable)
        return {frameTime};
    // Semi-fixed: Fiedler's `while (frameTime > 0) { step(min(frameTime, dt)); frameTime -= ...; }`.
    // A remainder below a billionth of dt is the sum's rounding, not time to step.
    double left = std::min(frameTime, maxFrameTime);
    std::vector<double> steps;
    while (left > 1e-9 * dt) {
        const double h = std::min(left, dt);
        steps.push_back(h);
        left -= h;
    }
    return steps;
}

} // namespace pba
