#pragma once
// A colliding swarm's heap, measured from its grains' positions alone: the angle its flanks stand
// at and how far two grains went into each other. `pba sim` prints them for the granular scene;
// its claims test holds them.
#include "pba/swarm.hpp"

namespace pba::study {

/// The mound's angle, degrees: around the axis along `up` through the grains' mean, the highest
/// grain centre in each ring one grain wide (at most 10,000 rings), out to the ring within which
/// 95% of the grains lie; a least-squares line through (ring's middle, height), and the atan of
/// its fall. A cone of half-angle 90° - theta reads theta; a flat layer reads 0.
double angleOfRepose(const Swarm& grains, const dvec3& up = dvec3(0.0, 1.0, 0.0));

/// The deepest overlap of two grains, in radii (0 when none overlap).
double deepestGrainOverlap(const Swarm& grains);

} // namespace pba::study
