// The rigid step for developers: one step of manyDice's pile taken again and again from the same
// state, so that two builds of the contact pipeline compare on the same work (a run of the whole
// throw does not: any change to the solver's order sends the dice elsewhere). The states are
// the throw's at 0.5 s (the dice landing in one island), 1.0 s (the slowest half second's) and
// 3.0 s (a heap falling asleep), on every core and on one.
// Run: build/bench/pba_pile_step_bench
#include <benchmark/benchmark.h>

#include <map>
#include <utility>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "pba/scene/scene.hpp"

namespace {

constexpr double kDt = 0.005;

/// The pile of `dice` after `seconds` of its throw, made once and kept.
const pba::World& pileAt(std::size_t dice, double seconds)
{
    static std::map<std::pair<std::size_t, double>, pba::World> piles;
    auto [it, made] = piles.try_emplace({dice, seconds});
    if (made) {
        pba::Scene scene = pba::manyDice(dice);
        pba::ContactSettings& s = scene.world.contactSettings();
        s.velocityIterations = s.maxVelocityIterations = 10; // as the bench's pile and Bullet's
        while (scene.world.time() < seconds - 0.5 * kDt)
            scene.world.step(kDt);
        it->second = std::move(scene.world);
    }
    return it->second;
}

void pileStep(benchmark::State& state, double seconds, int threads)
{
    const std::size_t dice = std::size_t(state.range(0));
    const pba::World& start = pileAt(dice, seconds);
    const tbb::global_control cores(tbb::global_control::max_allowed_parallelism,
                                    threads > 0 ? std::size_t(threads) : tbb::this_task_arena::max_concurrency());
    for (auto _ : state) {
        state.PauseTiming();
        pba::World world = start;
        state.ResumeTiming();
        world.step(kDt);
        benchmark::DoNotOptimize(world);
    }
    state.counters["steps_per_s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

} // namespace

BENCHMARK_CAPTURE(pileStep, landing_all_cores, 0.5, 0)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pileStep, slowest_all_cores, 1.0, 0)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pileStep, slowest_one_core, 1.0, 1)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pileStep, settling_all_cores, 3.0, 0)->Arg(1000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
