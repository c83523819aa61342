#pragma once
// `pba bench`'s swarm rows: blow-dryer-swarm's swarm with each integrator, on 1 thread and on all
// cores, in flight, landed and rested, beside the practical's heap Particles and the memory
// bandwidth's bound, at one size.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bench_rows.hpp"
#include "pba/world.hpp"

namespace pba::app::bench {

/// The states of blow-dryer-swarm a swarm row's windows start from, and the times the scene
/// reaches them. In flight: its first state, the rain falling (a quarter of it in the dryer's
/// cone). Landed, at 2 s: the rain after its first bounce (mean height 0.4 m, under 1% within
/// 10 cm of the floor in any step: few particles a block meet a surface), some in the jet and
/// the hole. Rested, at 8 s: nearly all of it on the floor (mean height 2 mm, 99.8% within
/// 1 cm; fountain-1m's state from about 4 s to its end), where the collision code runs for
/// every particle every step.
struct Phase {
    const char* name;
    double time;
};
constexpr std::array<Phase, 3> kPhases{{{"flight", 0.0}, {"landed", 2.0}, {"rested", 8.0}}};

/// The blow-dryer-swarm scene's world with n particles of the given integrator.
World swarmWorld(std::size_t n, Integrator integrator, int threads);

/// The start states of kPhases up to phase `last`: swarmWorld's semi-implicit Euler swarm stepped
/// to each phase's time (each row sets its own integrator and threads on a copy).
std::vector<World> phaseWorlds(std::size_t n, std::size_t last = kPhases.size() - 1);

/// The phase named `name` (one of kPhases), its index.
std::optional<std::size_t> phaseIndex(std::string_view name);

/// Peak memory per swarm particle: measured first, before anything else has raised the peak,
/// as the growth of the peak while an n-particle swarm world is built and stepped.
double bytesPerParticle(std::size_t n);

/// The rows of one size: the bound, the baseline (up to a million) and the swarm with each
/// integrator on 1 thread and on `cores`, in each phase; `bytes` is the swarm rows' bytes a
/// particle (bytesPerParticle, or 0 where not measured).
std::vector<Row> measureSize(std::size_t n, double minTime, int repeats, int cores, double bytes);

} // namespace pba::app::bench
