#pragma once
// A particle with a radius as the balls' contacts see it over one step. Private to the core.
#include "pba/math.hpp"

namespace pba::detail {

struct Ball {
    dvec3 x{0.0}, v{0.0};
    dvec3 start{0.0}; ///< where it was when the step began: its path is the line from there to x
    double since = 0.0; ///< when it was at `start`, as a fraction of the step (its last impact's, or 0)
    double inverseMass = 0.0; ///< 0: a fixed ball, which pushes and is not pushed
    double radius = 0.0;
    double cor = 1.0;
    double friction = 0.0;
    double restingSpeed = 0.0; ///< what its acceleration gives in one step, |a| dt
    /// Stepped by XPBD, which keeps it apart from the others inside its substeps: its contacts
    /// here only catch what those left, and start from nothing (a warm start would push apart
    /// what the substeps already hold apart).
    bool metInSubsteps = false;
    /// Joined to other bodies by springs (a rope's or a cloth's): an impact within the step
    /// changes its velocity but not its place, since its springs, not free flight, move it over
    /// the rest of the step (ball_impacts.hpp).
    bool sprung = false;
};

} // namespace pba::detail
