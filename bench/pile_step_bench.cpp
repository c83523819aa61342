// The rigid step for developers: ten steps of manyDice's pile taken again and again from the same
// state (after three untimed ones that size the copied world's lists), so that two builds of the contact pipeline compare on the same work (a run of the whole
// throw does not: any change to the solver's order sends the dice elsewhere). The states are
// the throw's at 0.5 s (the dice landing in one island), 1.0 s (the slowest half second's) and
// 3.0 s (a heap falling asleep), on every core and on one.
// Run: build/bench/pba_pile_step_bench
#include <benchmark/benchmark.h>

#include <map>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <utility>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "pba/scene/scene.hpp"

namespace {

constexpr double kDt = 0.005;
constexpr int kTimedSteps = 10; // 0.05 s of the throw from each saved state

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
        for (int k = 0; k < 3; ++k) // a copy's first steps size its scratch: not the work being compared
            world.step(kDt);
        state.ResumeTiming();
        for (int k = 0; k < kTimedSteps; ++k)
            world.step(kDt);
        benchmark::DoNotOptimize(world);
    }
    state.counters["steps_per_s"] =
        benchmark::Counter(double(state.iterations() * kTimedSteps), benchmark::Counter::kIsRate);
}

} // namespace

BENCHMARK_CAPTURE(pileStep, landing_all_cores, 0.5, 0)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pileStep, slowest_all_cores, 1.0, 0)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pileStep, slowest_one_core, 1.0, 1)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pileStep, settling_all_cores, 3.0, 0)->Arg(1000)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv)
{
#if defined(__GLIBC__)
    // Each repetition copies a saved world, whose lists are then freed: glibc would hand large
    // ones back to the kernel and fault them in again, page by page, in the next step (on this
    // virtual machine a fifth of the time). A running simulation keeps its lists; so does this.
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv))
        return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
