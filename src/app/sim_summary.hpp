#pragma once
// What `pba sim` prints at the end of a run: a row per body, then what the rigid bodies, the
// swarms and the blow dryer's jet did.
#include <vector>

#include "pba/scene/scene.hpp"
#include "study/jet_watch.hpp"
#include "study/rigid_watch.hpp"

namespace pba::app {

/// What the summary reports about each body, gathered as the run goes.
struct BodySummary {
    double startEnergy = 0.0;
    double highest = -INFINITY;
};

/// The run's summary on stdout: the scene's steps, a row per body (its final position and
/// speed, highest point, bounces and energy ratio), then the rigid bodies', the swarms' and
/// the jet's figures where the scene has them.
void printSummary(const Scene& scene, const World& world, const std::vector<BodySummary>& summary,
                  const study::JetWatch& jet, const study::RigidWatch& rigid);

} // namespace pba::app
