#include "bench_swarm.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <span>

#include <tbb/parallel_for.h>

#include "bench_timing.hpp"
#include "pba/large_array.hpp"
#include "pba/scene/scene.hpp"

namespace pba::app::bench {

namespace {

/// One row of a size: the step it times and how to restart it (both own its worlds), the steps
/// in each of its windows and their rates.
struct Subject {
    Row row;
    std::function<void()> step;
    std::function<void()> restart;
    long steps = 0;
    std::vector<double> rates;
};

/// The practical's way: one heap-allocated Particle (with its own mesh) per particle, stepped
/// one by one through the same world, forces and collisions.
World baselineWorld(std::size_t n)
{
    World swarm = swarmWorld(n, Integrator::SemiImplicitEuler, 1);
    World world = swarm;
    world.swarm(0) = Swarm(SwarmDesc{}); // the same world, with the particles as heap objects instead
    for (std::size_t i = 0; i < n; ++i) {
        Particle p;
        p.setPos(dvec3(swarm.swarm(0).position(i)));
        p.setVel(dvec3(swarm.swarm(0).velocity(i)));
        p.setCor(swarm.swarm(0).restitution());
        world.addParticle(p);
    }
    return world;
}

/// One pass of the bandwidth bound's in-place update a[i] = a[i] * s + t over the swarm state's
/// size (24 n bytes, so a = 6 n floats) on all cores. Counting 8 bytes moved per element, a pass
/// moves 48 n bytes: what n particle-steps must move (position and velocity, read and written, in
/// float), so a pass counts as n particle-steps. Its memory is allocated as a swarm's state is
/// (LargeArrayAllocator: in huge pages where the kernel has them), so that the two are compared on
/// the same pages.
void boundPass(LargeArray<float>& a)
{
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, a.size(), 1 << 16), [&](const auto& range) {
        for (std::size_t i = range.begin(); i < range.end(); ++i)
            a[i] = a[i] * 0.999f + 0.001f;
    });
}

/// Peak resident memory of this process so far (VmHWM), bytes.
double peakResidentBytes()
{
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmHWM:", 0) == 0)
            return std::stod(line.substr(6)) * 1024.0;
    return 0.0;
}

} // namespace

World swarmWorld(std::size_t n, Integrator integrator, int threads)
{
    World world = loadScene("blow-dryer-swarm").world;
    SwarmDesc desc = world.swarm(0).desc();
    desc.count = n;
    desc.integrator = integrator;
    world.swarm(0) = Swarm(desc);
    world.setThreads(threads);
    return world;
}

std::vector<World> phaseWorlds(std::size_t n, std::size_t last)
{
    std::vector<World> worlds;
    World world = swarmWorld(n, Integrator::SemiImplicitEuler, 0);
    long done = 0;
    for (const Phase& phase : std::span(kPhases).first(last + 1)) {
        for (const long steps = std::lround(phase.time / 0.002); done < steps; ++done)
            world.step(0.002);
        worlds.push_back(world);
    }
    return worlds;
}

std::optional<std::size_t> phaseIndex(std::string_view name)
{
    for (std::size_t p = 0; p < kPhases.size(); ++p)
        if (name == kPhases[p].name)
            return p;
    return std::nullopt;
}

double bytesPerParticle(std::size_t n)
{
    const double before = peakResidentBytes();
    World world = swarmWorld(n, Integrator::SemiImplicitEuler, 0);
    world.step(0.002);
    return (peakResidentBytes() - before) / double(n);
}

/// The rows of one size: the bound, the baseline (up to a million: a million heap Particles take
/// about a gigabyte) and the swarm with each integrator on 1 thread and on all cores. Their
/// windows are taken in turn, round after round, rather than row after row: this machine's speed
/// drifts by a third over seconds, and a bound measured seconds before a row made the row's
/// ratio swing with the drift (0.48 to 0.72 in three runs); interleaved, a slow spell slows
/// every row alike. Every window of a row is the same work: its world restarts from the scene's
/// first state and takes as many steps as filled a first, calibrating window (stepping on
/// instead, the first windows of a small N timed the rain in flight and the later ones the rain
/// landing, twice the work a step). So windows differ only by what else the machine is doing,
/// and every rate, the bound's as the issue defines it and each row's alike, is its best
/// window (the reasoning of Python's timeit). A row's median against the bound's best made the
/// ratio at 1e7 read 0.65 in a run whose rows were 0.86 to 1.01 of the bound window taken
/// beside them, round by round; best against best over 3 windows read 0.72 to 1.06 from run to
/// run, over 6 0.86 to 1.00, and 0.88 to 1.07 with every window the same work.
std::vector<Row> measureSize(std::size_t n, double minTime, int repeats, int cores, double bytes)
{
    LargeArray<float> state(6 * n, 1.0f); // as a swarm's memory
    std::vector<Subject> subjects;
    // The bound's pass is the same work whatever the array holds: nothing to restart.
    subjects.push_back(
        {Row{"bound", "", "", n, cores, 0.0, 24.0, 1.0, 0.0}, [&state] { boundPass(state); }, [] {}, 0, {}});
    const auto add = [&](Row row, World world) {
        Restartable r = restartable(std::move(world));
        subjects.push_back({std::move(row), std::move(r.step), std::move(r.restart), 0, {}});
    };
    if (n <= 1000000)
        add(Row{"baseline", "semi-implicit-euler", "flight", n, 1, 0.0, 0.0, 0.0, 1.0}, baselineWorld(n));
    const std::vector<World> starts = phaseWorlds(n);
    for (std::size_t p = 0; p < kPhases.size(); ++p)
        for (Integrator integrator : kAllIntegrators)
            for (int threads : {1, cores}) {
                World world = starts[p];
                world.swarm(0).setIntegrator(integrator);
                world.setThreads(threads);
                add(Row{"swarm", std::string(integratorName(integrator)), kPhases[p].name, n, threads, 0.0, bytes, 0.0,
                        0.0},
                    std::move(world));
                if (threads == cores)
                    break;
            }
    timeInTurn(subjects, n, minTime, repeats);
    const std::vector<double>& boundRates = subjects.front().rates; // the bound is pushed first
    const double bound = best(boundRates);
    const auto baselineRow = std::find_if(subjects.begin(), subjects.end(),
                                          [](const Subject& subject) { return subject.row.layout == "baseline"; });
    const double baseline = baselineRow != subjects.end() ? best(baselineRow->rates) : 0.0;
    std::vector<Row> rows;
    for (Subject& subject : subjects) {
        Row row = subject.row;
        row.rate = best(subject.rates);
        row.medianRate = median(subject.rates);
        row.ofBound = row.rate / bound;
        // The baseline is timed in flight only (a million heap Particles would take minutes to
        // land): the landed rows have no ratio to it.
        row.ofBaseline = baseline > 0.0 && row.layout != "bound" && row.phase == "flight" ? row.rate / baseline : 0.0;
        rows.push_back(row);
    }
    return rows;
}

} // namespace pba::app::bench
