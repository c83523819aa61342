// How long the headless renderer takes to draw N particles at 1280x720 (CPU rasteriser
// here, a real GPU elsewhere). Run: build/bench/pba_render_bench
#include <benchmark/benchmark.h>

#include <random>

#include "render/offscreen.hpp"

namespace {

void drawSprites(benchmark::State& state)
{
    static pba::render::OffscreenRenderer renderer(1280, 720, false);
    renderer.camera() = pba::render::OrbitCamera::framing(glm::vec3(-2, 0, -2), glm::vec3(2, 4, 2));
    pba::render::DrawList list;
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(-2.0f, 2.0f);
    for (long i = 0; i < state.range(0); ++i)
        list.sprites.push_back({glm::vec3(u(rng), 2.0f + u(rng), u(rng)), 0.02f, glm::vec4(0.3f, 0.6f, 0.9f, 1.0f)});
    list.addBoxEdges(glm::vec3(-2, 0, -2), glm::vec3(2, 4, 2), glm::vec4(1.0f));
    for (auto _ : state)
        benchmark::DoNotOptimize(renderer.renderList(list)); // includes reading the pixels back
    state.counters["particles/s"] = benchmark::Counter(double(state.range(0)), benchmark::Counter::kIsIterationInvariantRate);
}

} // namespace

BENCHMARK(drawSprites)->Arg(1000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
