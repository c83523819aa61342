// The narrow phase for developers: nanoseconds per box-box pair, resting (a face manifold of up
// to four points) and in the air (near enough for the broad phase, further apart than the
// margin), with and without the SAT cache a contact cache would keep for the pair.
// Run: build/bench/pba_narrow_phase_bench
#include <benchmark/benchmark.h>

#include <numbers>

#include "core/contact/narrow_phase.hpp"

namespace {

using namespace pba::contact;
using pba::dmat3;
using pba::dvec3;

constexpr double kMargin = 0.02; // m: a speculative distance of the order the solver would ask

dmat3 turned(double degrees, const dvec3& axis)
{
    return glm::mat3_cast(glm::angleAxis(degrees * std::numbers::pi / 180.0, glm::normalize(axis)));
}

/// Two 30 cm dice: B over A at `height` between their centres, turned 20 degrees about y and
/// tilted a little (a resting die is never quite flat), so B's bottom face clips against A's top
/// into an octagon of points to reduce.
void boxBox(benchmark::State& state, double height, bool cached)
{
    const CollisionShape die = CollisionShape::of(pba::Shape::box(dvec3(0.3)));
    const Transform ta{dvec3(0.0), dmat3(1.0)};
    const Transform tb{{0.02, height, -0.01}, turned(20, {0, 1, 0}) * turned(0.2, {1, 0, 1})};
    SatCache cache;
    int points = 0;
    for (auto _ : state) {
        const Manifold m = collide(die, ta, die, tb, kMargin, cached ? &cache : nullptr);
        points = m.count;
        benchmark::DoNotOptimize(m);
    }
    state.counters["points"] = points;
    state.SetItemsProcessed(state.iterations());
}

void resting(benchmark::State& state)
{
    boxBox(state, 0.3, state.range(0) != 0);
}

void inTheAir(benchmark::State& state)
{
    boxBox(state, 0.35, state.range(0) != 0);
}

/// Two dice crossed edge to edge (one turned 45 degrees about z, the other about x), touching.
void crossedEdges(benchmark::State& state)
{
    const CollisionShape die = CollisionShape::of(pba::Shape::box(dvec3(0.3)));
    const Transform ta{dvec3(0.0), turned(45, {0, 0, 1})};
    const Transform tb{{0.01, 0.3 * std::numbers::sqrt2 - 0.001, 0.02}, turned(45, {1, 0, 0})};
    SatCache cache;
    for (auto _ : state)
        benchmark::DoNotOptimize(collide(die, ta, die, tb, kMargin, &cache));
    state.SetItemsProcessed(state.iterations());
}

} // namespace

BENCHMARK(resting)->ArgName("cache")->Arg(0)->Arg(1);
BENCHMARK(inTheAir)->ArgName("cache")->Arg(0)->Arg(1);
BENCHMARK(crossedEdges);
BENCHMARK_MAIN();
