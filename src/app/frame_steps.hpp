#pragma once
// Synthetic frames: the world stepped to exactly a simulated time, with no real clock in the
// way. `pba render` draws every frame so, and the viewer's capture mode (`pba view --time T`)
// reaches T so, which is why the two show the same state at the same time on any machine.
#include <cstdint>
#include <string>

#include "pba/blow_up_watch.hpp"
#include "pba/frame_clock.hpp"
#include "pba/scene/scene.hpp"

namespace pba::app {

/// The steps of dt that bring the world's current state to t or just past it (0 if it is there).
/// Counted from the world's time, so a dt changed along the way is still respected.
std::uint64_t stepsToReach(const World& world, double t, double dt);

/// The alpha that interpolates the world's last two states back to t (1 if there is one state).
double alphaAt(const World& world, double t);

/// Synthetic frames are not late, so no clamp or step cap applies (those guard a real-time
/// loop), and each frame is drawn at exactly its time t rather than at the sum of the frame
/// times before it (whose rounding drops a step now and then): the world takes the steps that
/// bring its current state to t or just past it, and the drawn state is interpolated back to t,
/// as the window's clock interpolates between the last two states. Returns that alpha. Throws
/// BlowUpError at a step that blows up (the world's checks, then `watch`'s).
double stepToFrame(Scene& scene, double t, BlowUpWatch& watch);

/// A synthetic frame of frameTime with the semi-fixed or variable clock (frameSteps, with the
/// scene's dt): the steps it takes, with nothing left over, so the state drawn is the last one
/// (alpha 1). A frame time of zero takes no step. Throws BlowUpError as stepToFrame does.
double stepFrameWith(ClockKind clock, Scene& scene, double frameTime, BlowUpWatch& watch);

/// `--clock NAME`: the clock, or UsageError naming the option, the value and the names it takes.
ClockKind parseClockOption(const std::string& name);
/// The option's help text, the same for view and render.
extern const char* const kClockOptionHelp;

} // namespace pba::app
