#pragma once
#include "pba/math.hpp"

namespace pba {

/// The dynamic state that the integrators advance and the renderer interpolates
/// ("Fix Your Timestep", the final touch: blend the previous and current State).
struct State {
    dvec3 pos{0.0};
    dvec3 vel{0.0};
};

/// Linear blend for rendering between two physics states; alpha in [0, 1).
inline State interpolate(const State& previous, const State& current, double alpha)
{
    return {previous.pos + (current.pos - previous.pos) * alpha,
            previous.vel + (current.vel - previous.vel) * alpha};
}

} // namespace pba
