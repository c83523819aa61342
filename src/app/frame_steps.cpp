#include "frame_steps.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "command.hpp"
#include "pba/clock.hpp"

namespace pba::app {

std::uint64_t stepsToReach(const World& world, double t, double dt)
{
    // The tolerance keeps t = k dt, rounded a hair above k dt, from asking for step k + 1.
    const double steps = std::ceil((t - world.time()) / dt - 1e-9);
    return steps > 0.0 ? static_cast<std::uint64_t>(steps) : 0;
}

double alphaAt(const World& world, double t)
{
    const double span = world.time() - world.previousTime();
    return span > 0.0 ? std::clamp((t - world.previousTime()) / span, 0.0, 1.0) : 1.0;
}

double stepToFrame(Scene& scene, double t, BlowUpWatch& watch)
{
    for (std::uint64_t n = stepsToReach(scene.world, t, scene.dt); n > 0; --n) {
        scene.world.step(scene.dt);
        watch.check(scene.world);
    }
    return alphaAt(scene.world, t);
}

double stepFrameWith(ClockKind clock, Scene& scene, double frameTime, BlowUpWatch& watch)
{
    if (frameTime <= 0.0)
        return 1.0;
    for (const double h : frameSteps(clock, scene.dt, frameTime, FixedTimestepClock::kDefaultMaxFrameTime)) {
        scene.world.step(h);
        watch.check(scene.world);
    }
    return 1.0;
}

ClockKind parseClockOption(const std::string& name)
{
    if (const auto clock = clockFromName(name))
        return *clock;
    throw UsageError(fmt::format("--clock: unknown clock '{}' (fixed, semi-fixed or variable)", name));
}

const char* const kClockOptionHelp =
    "The physics clock (Fiedler's \"Fix Your Timestep\"): fixed (default: whole steps of dt, the rest of a frame "
    "drawn by interpolation), semi-fixed (steps of dt and a shorter one for the rest of each frame) or variable (one "
    "step of each frame's time: the naive clock, its physics changes with the frame rate)";

} // namespace pba::app
