#include "bench_granular.hpp"

#include <cmath>
#include <functional>
#include <span>

#include "bench_timing.hpp"
#include "pba/scene/scene.hpp"

namespace pba::app::bench {

namespace {

/// What a granular row times: the granular scene's grains at half its size (5 mm), n of them,
/// from a sparse layer 23 cm
/// deep over a square floor holding a million on 14 m^2 (a grain's share of the layer is 27
/// times a cube of its radius, so few start inside another), after 10 steps: the lowest grains
/// on the floor and touching, the others falling onto them. (A million grains take about a second
/// a step, so the rows start there rather than after the layer has landed.)
World granularWorld(std::size_t n, bool collide, int threads)
{
    World world = loadScene("granular").world;
    SwarmDesc desc = world.swarm(0).desc();
    const double r = 0.005, depth = 0.23, side = 3.8 * std::sqrt(double(n) / 1e6);
    desc.count = n;
    desc.radius = r;
    desc.collide = collide;
    // Without collisions the row is the plain swarm step the target is a fraction of: without the
    // room's friction too.
    if (!collide)
        desc.friction = 0.0;
    desc.regionMin = dvec3(-side / 2, r, -side / 2);
    desc.regionMax = dvec3(side / 2, depth, side / 2);
    world.swarm(0) = Swarm(desc);
    world.setRoom({dvec3(-side / 2 - 0.1, 0.0, -side / 2 - 0.1), dvec3(side / 2 + 0.1, 1.0, side / 2 + 0.1)});
    world.setThreads(threads);
    for (int step = 0; step < 10; ++step)
        world.step(0.002);
    return world;
}

struct Subject {
    std::function<void()> step, restart;
    long steps = 0;
    std::vector<double> rates;
};

} // namespace

std::vector<GranularRow> measureGranular(bool quick, double minTime, int repeats, int cores)
{
    std::vector<GranularRow> rows;
    for (const std::size_t n : std::span(kGranularSizes).first(quick ? 1 : 2)) {
        std::vector<Subject> subjects;
        for (const bool collide : {true, false}) {
            Restartable r = restartable(granularWorld(n, collide, 0));
            subjects.push_back({std::move(r.step), std::move(r.restart), 0, {}});
        }
        timeInTurn(subjects, n, minTime, repeats);
        rows.push_back({n, cores, best(subjects[0].rates), best(subjects[1].rates), median(subjects[0].rates),
                        median(subjects[1].rates)});
    }
    return rows;
}

} // namespace pba::app::bench
