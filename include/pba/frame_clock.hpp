#pragma once
// The three clocks a program can drive its physics with, as Glenn Fiedler's "Fix Your Timestep"
// tells them, so that a student can run one scene with each and see the difference:
//  - fixed: whole steps of dt from an accumulator, the rest of the frame drawn by interpolating
//    the last two states (FixedTimestepClock). The physics depends on dt and the step count alone.
//  - semi-fixed: steps of dt, and one shorter step for what is left of the frame. Never a step
//    longer than dt, so it stays stable, but the steps depend on the frame rate.
//  - variable: one step of the whole frame time, the naive `x += v * frame_time`. The physics
//    depends on every frame's length, and one slow frame is one huge step.
#include <array>
#include <optional>
#include <string_view>
#include <vector>

namespace pba {

enum class ClockKind { Fixed, SemiFixed, Variable };

inline constexpr std::array<ClockKind, 3> kClockKinds{ClockKind::Fixed, ClockKind::SemiFixed, ClockKind::Variable};

/// "fixed", "semi-fixed", "variable".
std::string_view clockName(ClockKind kind);
std::optional<ClockKind> clockFromName(std::string_view name);

/// The steps a frame of frameTime takes with the semi-fixed or the variable clock, their lengths
/// in order (they sum to the frame time). The semi-fixed clock first clamps the frame to
/// maxFrameTime, as the fixed clock does, against the spiral of death; the variable clock takes
/// the frame as it comes: that is its lesson. Neither keeps a remainder, so neither interpolates.
/// Throws std::invalid_argument for the fixed clock (FixedTimestepClock is its state), or a frame
/// time, dt or maxFrameTime that is not finite and positive.
std::vector<double> frameSteps(ClockKind kind, double dt, double frameTime, double maxFrameTime);

} // namespace pba
