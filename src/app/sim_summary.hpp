#pragma once
// What `pba sim` prints at the end of a run: a row per body, then what the rigid bodies, the
// swarms and the blow dryer's jet did.
#include <vector>

#include "pba/blow_up_watch.hpp"
#include "pba/scene/scene.hpp"
#include "render/body_groups.hpp"
#include "study/ball_watch.hpp"
#include "study/exact_solution.hpp"
#include "study/jet_watch.hpp"
#include "study/rigid_watch.hpp"

namespace pba::app {

/// What the summary reports about each body, gathered as the run goes.
struct BodySummary {
    double startEnergy = 0.0;
    dvec3 startMomentum{0.0};
    double highest = -INFINITY;
};

/// What `pba sim` watches over a run, each after every step: whether it blows up, and what the
/// jet, the rigid bodies and the balls did.
struct RunWatches {
    explicit RunWatches(const Scene& scene);
    /// After every step; throws BlowUpError (BlowUpWatch::check) before the others look.
    void record(const World& world);
    /// After the last step.
    void finish(const World& world) { balls.finish(world); }
    /// The scene's ropes and cloths and every other body: for the watches and the summary alike.
    render::BodyGroups groups;
    BlowUpWatch blowUp;
    study::JetWatch jet;
    study::RigidWatch rigid;
    study::BallWatch balls;
    /// The particles whose exact motion is known from the start (study::ExactSolution), with it.
    std::vector<std::pair<std::size_t, study::ExactSolution>> exact;
};

/// The run's summary on stdout: the scene's steps, a row per body that is no rope's or cloth's
/// (its final position and speed, highest point, bounces and energy ratio), a row per rope and
/// cloth (its totals) and a line of where its particles end, the whole scene's energy and
/// momentum and its largest step's rise, each particle beside its exact solution where it has
/// one, then the rigid bodies', the balls', the swarms' and the jet's figures where the scene has
/// them. Where the blow dryer pushed a body, its energy
/// ratio says so: the dryer's work, not an error; the scene's line gives that work
/// (BlowUpWatch's sum of its power) and the ratio without it. `everyParticle` adds
/// a row per particle of each rope and cloth.
void printSummary(const Scene& scene, const World& world, const std::vector<BodySummary>& summary,
                  const RunWatches& watches, bool everyParticle = false);

} // namespace pba::app
