#include "frame_steps.hpp"

#include <algorithm>
#include <cmath>

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

double stepToFrame(Scene& scene, double t, const BlowUpWatch& watch)
{
    for (std::uint64_t n = stepsToReach(scene.world, t, scene.dt); n > 0; --n) {
        scene.world.step(scene.dt);
        watch.check(scene.world);
    }
    return alphaAt(scene.world, t);
}

} // namespace pba::app
