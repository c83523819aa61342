// The swarm kernels for developers: one step of the blow-dryer swarm per integrator and size,
// on one thread and on all cores, and the in-place update that bounds it.
// Run: build/bench/pba_swarm_bench   (pba bench prints the same comparison as a table)
#include <benchmark/benchmark.h>

#include <tbb/parallel_for.h>

#include "pba/scene/scene.hpp"

namespace {

pba::World swarmWorld(std::size_t n, pba::Integrator integrator, int threads)
{
    pba::World world = pba::loadScene("blow-dryer-swarm").world;
    pba::SwarmDesc desc = world.swarm(0).desc();
    desc.count = n;
    desc.integrator = integrator;
    world.swarm(0) = pba::Swarm(desc);
    world.setThreads(threads);
    return world;
}

void swarmStep(benchmark::State& state)
{
    const auto n = static_cast<std::size_t>(state.range(0));
    pba::World world = swarmWorld(n, static_cast<pba::Integrator>(state.range(1)), static_cast<int>(state.range(2)));
    for (auto _ : state)
        world.step(0.002);
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(n));
    state.SetLabel(std::string(pba::integratorName(world.swarm(0).integrator())));
}

void inPlaceUpdate(benchmark::State& state)
{
    std::vector<float> a(6 * static_cast<std::size_t>(state.range(0)), 1.0f);
    for (auto _ : state)
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, a.size(), 1 << 16), [&](const auto& r) {
            for (std::size_t i = r.begin(); i < r.end(); ++i)
                a[i] = a[i] * 0.999f + 0.001f;
        });
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(a.size()) * 8);
}

} // namespace

BENCHMARK(swarmStep)
    ->ArgsProduct({{100000, 1000000}, {0, 1, 2, 3}, {1, 0}})
    ->ArgNames({"n", "integrator", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(inPlaceUpdate)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
