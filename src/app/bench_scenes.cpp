#include "bench_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <utility>

#include "bench_pile.hpp"
#include "bench_timing.hpp"
#include "pba/scene/scene.hpp"
#include "pba/spring_network.hpp"

namespace pba::app::bench {

namespace {

/// cloth-in-the-dryer at kClothSide x kClothSide (resizedClothInTheDryer): one system of springs
/// (structural, shear and bending) on `integrator`, gravity, the blow dryer and the room.
World clothWorld(Integrator integrator, int threads)
{
    World world = resizedClothInTheDryer(kClothSide).world;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        world.body(i).setIntegrator(integrator);
    world.setThreads(threads);
    return world;
}

/// The springs of a world's rope and cloth networks.
std::size_t springCount(const World& world)
{
    struct Counter final : ForceVisitor {
        std::size_t springs = 0;
        void visit(const SpringNetwork& network) override { springs += network.size(); }
        void visit(const TwoBodySpring&) override { ++springs; }
    } counter;
    for (std::size_t i = 0; i < world.forceCount(); ++i)
        world.force(i).accept(counter);
    return counter.springs;
}

/// The pile rows' span from the throw: the landing and the settling (bench/peers/pile.py's default).
constexpr double kPileDuration = 4.0;

} // namespace

std::vector<ClothRow> measureCloth(double minTime, int repeats, int cores)
{
    struct ClothSubject {
        ClothRow row;
        std::shared_ptr<World> world; ///< the stepped one, for what its last step cost
        std::function<void()> step, restart;
        long steps = 0;
        std::vector<double> rates;
    };
    std::vector<ClothSubject> subjects;
    for (const ClothMethod& method : kClothMethods)
        for (int threads : {1, cores}) {
            auto first = std::make_shared<const World>(clothWorld(method.integrator, threads));
            auto world = std::make_shared<World>(*first);
            ClothRow row;
            row.integrator = method.integrator;
            row.dt = method.dt;
            row.threads = threads;
            row.particles = world->bodyCount();
            row.springs = springCount(*world);
            const double dt = method.dt;
            subjects.push_back({row, world, [world, dt] { world->step(dt); }, [world, first] { *world = *first; }, 0, {}});
            if (threads == cores)
                break;
        }
    timeInTurn(subjects, 1, minTime, repeats);
    std::vector<ClothRow> rows;
    for (ClothSubject& s : subjects) {
        s.row.stepsPerSecond = best(s.rates);
        s.row.medianStepsPerSecond = median(s.rates);
        s.row.iterations = s.world->lastImplicitIterations();
        s.row.substeps = s.row.integrator == Integrator::Xpbd ? s.world->xpbdSubsteps() : 0;
        rows.push_back(s.row);
    }
    return rows;
}

namespace {

/// Steps the world through run.spans spans of run.spanSteps steps, timing each, and records the
/// slowest span's rate, where it starts and the whole run's rate in `run`.
void timeRun(World& world, double dt, SpanRun& run)
{
    const SpanTimes times = timeSpans(world, dt, run.spans, run.spanSteps);
    run.stepsPerSecond = times.slowest;
    run.overallStepsPerSecond = double(run.spans) * run.spanSteps / times.total;
    run.slowestFrom = times.slowestSpan * run.spanSteps * dt;
}

} // namespace

PileRun runPile(std::size_t dice, bool quick, int cores)
{
    Scene scene = manyDice(dice);
    World& world = scene.world;
    world.setThreads(0);
    usePileSolver(world, kPileIterations);
    PileRun pile{dice, {}};
    SpanRun& run = pile.run;
    run.threads = cores;
    run.spanSteps = quick ? 10 : static_cast<int>(std::lround(0.5 / scene.dt));
    run.spans = quick ? 2 : static_cast<int>(std::lround(kPileDuration / 0.5));
    timeRun(world, scene.dt, run);
    return pile;
}

/// The rain in flight is the cheap part; from about 4 s nearly every particle lies on the floor,
/// bouncing in place within the contact tolerance, and some slide around the hole's shaft: the
/// collision code runs for all of them every step, and its slowest second is one of those. A
/// program must keep up with its slowest second, so that is the row's rate; the whole run's
/// average is beside it.
SceneRun runScene(bool quick, int cores)
{
    Scene scene = loadScene("fountain-1m");
    World& world = scene.world;
    world.setThreads(0);
    SceneRun fountain;
    SpanRun& run = fountain.run;
    run.threads = cores;
    run.spanSteps = quick ? 4 : static_cast<int>(std::lround(1.0 / scene.dt));
    run.spans = quick ? 2 : static_cast<int>(std::lround(scene.duration));
    timeRun(world, scene.dt, run);
    fountain.n = world.swarm(0).size();
    fountain.integrator = std::string(integratorName(world.swarm(0).integrator()));
    return fountain;
}

} // namespace pba::app::bench
