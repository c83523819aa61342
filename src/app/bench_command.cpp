// `pba bench`: particle-steps per second of the swarm layout against the practical's
// vector of heap Particles and against the memory-bandwidth bound, measured in one run, then
// the scene rows (bench_swarm.hpp, bench_scenes.hpp); or, with --phases, where a swarm step's
// time goes; or, with --peer-worker, the swarm driven by bench/peers/run.py; or, with
// --pile-worker, a pile of dice driven by bench/peers/pile.py (bench_pile.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench_granular.hpp"
#include "bench_pile.hpp"
#include "bench_scenes.hpp"
#include "bench_swarm.hpp"
#include "bench_timing.hpp"
#include "bench_worker.hpp"
#include "command.hpp"
#include "flag_values.hpp"
#include "scene_options.hpp"
#include "pba/blow_dryer.hpp"
#include "pba/scene/scene.hpp"

namespace pba::app {

namespace {

using namespace bench;

struct BenchOptions {
    bool json = false;
    bool quick = false;
    int windows = 0; ///< 0: the default (6, one with --quick)
    std::vector<double> sizes;
    std::string sizeList; ///< --sizes as typed: one word, so that a repeated --sizes is refused
    bool peerWorker = false; ///< --peer-worker: one row, windows on request (bench/peers/run.py)
    std::string phase = "flight";
    bool phases = false; ///< --phases: where a swarm step's time goes, instead of the rows
    std::string integrator = "semi-implicit-euler"; ///< --phases' and --peer-worker's integrator
    bool integratorGiven = false;                   ///< --integrator was on the command line
    bool pileWorker = false; ///< --pile-worker: a pile of --dice dice, windows on request (bench/peers/pile.py)
    long long dice = 1000; ///< signed: CLI11 reads -1 into an unsigned count as 2^64 - 1
    int iterations = kPileIterations; ///< --iterations: the pile worker's velocity sweeps a step
};

/// Statistics of the swarm the peers are validated against (bench/peers/): the mean height, the
/// fractions of the particles in the dryer's cone (insideBlowDryerCone, in double) and in its
/// hole's shaft, and an order-free checksum of the state's bits (the sum of the six arrays' floats
/// read as 32-bit integers, modulo 2^64), which two implementations share only when their states
/// are the same to the bit.
nlohmann::json swarmStatistics(const World& world, double t)
{
    const Swarm& swarm = world.swarm(0);
    const BlowDryerField field = blowDryers(world).front().field;
    const std::size_t n = swarm.size();
    double height = 0.0;
    std::size_t inCone = 0, inShaft = 0;
    std::uint64_t bits = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3<float> x = swarm.position(i), v = swarm.velocity(i);
        height += double(x.y);
        inCone += insideBlowDryerCone(field, dvec3(x)) ? 1 : 0;
        inShaft += insideBlowDryerShaft(field, dvec3(x)) ? 1 : 0;
        for (const float c : {x.x, x.y, x.z, v.x, v.y, v.z}) {
            std::uint32_t word;
            std::memcpy(&word, &c, sizeof word);
            bits += word;
        }
    }
    const double count = double(std::max<std::size_t>(n, 1));
    return {{"t", t}, {"n", n}, {"mean_height", height / count}, {"cone_fraction", double(inCone) / count},
            {"shaft_fraction", double(inShaft) / count}, {"state_bits_sum", bits}};
}

/// --integrator for a swarm: a spring system's method has no springs to step in one (a scene's
/// swarm refuses it too), and would run as semi-implicit Euler under its name.
Integrator swarmIntegratorFlag(const std::string& name)
{
    const Integrator integrator = integratorFlag(name);
    if (isSpringSystemMethod(integrator))
        throw UsageError(fmt::format("--integrator: {} steps particles joined by springs; a swarm has none: take "
                                     "forward-euler, semi-implicit-euler, velocity-verlet or rk4",
                                     integratorName(integrator)));
    return integrator;
}

/// `pba bench --peer-worker`: the swarm of blow-dryer-swarm (--integrator's) on all cores, at
/// the one size given, from the phase's start state (kPhases), driven line by line from standard
/// input by bench/peers/run.py, which takes its windows in turn with the Python peers' (its own
/// process, so interleaved across them):
///   window STEPS   restart from the start state, time STEPS steps, print {"seconds", "steps", ...}
///   stats          print swarmStatistics of the current state
/// Each answer is one JSON line; the first line, {"ready": ...}, follows the setup.
int runPeerWorker(const BenchOptions& options)
{
    if (options.sizes.size() != 1)
        throw UsageError("--peer-worker: give exactly one size with --sizes");
    const double size = options.sizes.front();
    if (!(size >= 1.0 && size <= 1e8 && size == std::floor(size)))
        throw UsageError(fmt::format("--sizes: the size must be a whole number from 1 to 1e8, got {}", size));
    const std::optional<std::size_t> phase = phaseIndex(options.phase);
    if (!phase)
        throw UsageError(fmt::format("--phase: flight, landed or rested, got '{}'", options.phase));
    const Integrator integrator = swarmIntegratorFlag(options.integrator); // before the start states take minutes
    const auto n = static_cast<std::size_t>(size);
    const double startTime = kPhases[*phase].time;
    World first = std::move(phaseWorlds(n, *phase).back());
    first.swarm(0).setIntegrator(integrator); // the start states are semi-implicit Euler's, whatever it is
    World world = first;
    double t = startTime;
    const nlohmann::json ready{{"ready", true},
                               {"n", n},
                               {"phase", options.phase},
                               {"t", t},
                               {"integrator", std::string(integratorName(first.swarm(0).integrator()))},
                               {"threads", machineCores()}};
    const auto window = [&](std::istringstream& args, const std::string& line) -> nlohmann::json {
        const long steps = windowSteps("--peer-worker", args, line);
        world = first;
        const auto start = Clock::now();
        for (long k = 0; k < steps; ++k)
            world.step(0.002);
        const double elapsed = seconds(start);
        t = startTime + 0.002 * double(steps);
        return {{"seconds", elapsed}, {"steps", steps}, {"t", t},
                {"particle_steps_per_s", double(n) * double(steps) / elapsed}};
    };
    const auto stats = [&](std::istringstream&, const std::string&) { return swarmStatistics(world, t); };
    return serveWorker("--peer-worker", ready, {{"window", "window STEPS", window}, {"stats", "stats", stats}});
}

/// --phases: the swarm on all cores with --integrator (semi-implicit Euler unless told), in each
/// of kPhases (the same start states whatever the integrator), each step's time split by phase
/// (SwarmPhaseTimes: thread-time summed over the threads, so on 2 threads the phases add up to
/// about twice the step's wall time).
int runPhases(const BenchOptions& options)
{
    const std::vector<double> sizes = options.sizes.empty() ? std::vector<double>{1e6} : options.sizes;
    const Integrator integrator = swarmIntegratorFlag(options.integrator);
    const int steps = options.quick ? 10 : 200;
    nlohmann::json out;
    out["results"] = nlohmann::json::array();
    std::string table = fmt::format("{:>9} {:<7} {:>8}", "n", "phase", "steps/s");
    for (const char* name : SwarmPhaseTimes::kNames)
        table += fmt::format(" {:>18}", fmt::format("{} ms", name));
    table += "\n";
    for (double size : sizes) {
        if (!(size >= 1.0 && size <= 1e8 && size == std::floor(size)))
            throw UsageError(fmt::format("--sizes: each size must be a whole number from 1 to 1e8, got {}", size));
        const auto n = static_cast<std::size_t>(size);
        std::vector<World> starts = phaseWorlds(n);
        for (std::size_t which = 0; which < kPhases.size(); ++which) {
            const char* phase = kPhases[which].name;
            World& world = starts[which];
            world.setThreads(0);
            world.swarm(0).setIntegrator(integrator);
            {
                // One untimed step of a copy: the phase clock measures its rate (5 ms) at its
                // first use, which the first phase's steps per second would otherwise include.
                SwarmPhaseTimes untimed;
                World warm = world;
                warm.swarm(0).setPhaseTimes(&untimed);
                warm.step(0.002);
            }
            SwarmPhaseTimes times;
            world.swarm(0).setPhaseTimes(&times);
            const auto start = Clock::now();
            for (int k = 0; k < steps; ++k)
                world.step(0.002);
            const double rate = steps / seconds(start);
            nlohmann::json row{{"layout", "phases"}, {"integrator", std::string(integratorName(integrator))},
                               {"phase", phase}, {"n", n}, {"steps_per_s", rate}};
            table += fmt::format("{:>9} {:<7} {:>8.1f}", n, phase, rate);
            double total = 0.0;
            for (const auto& t : times.nanoseconds)
                total += double(t.load());
            for (std::size_t p = 0; p < SwarmPhaseTimes::kCount; ++p) {
                const double ms = double(times.nanoseconds[p].load()) * 1e-6 / steps;
                std::string key = SwarmPhaseTimes::kNames[p];
                std::replace(key.begin(), key.end(), ' ', '_'); // "surface_test_ms"
                row[key + "_ms"] = ms;
                table += fmt::format(" {:>10.3f} ({:>4.1f}%)", ms, 100.0 * double(times.nanoseconds[p].load()) / total);
            }
            table += "\n";
            out["results"].push_back(row);
        }
    }
    if (options.json)
        fmt::print("{}\n", out.dump(2));
    else
        fmt::print("{}({}, blow-dryer-swarm, all cores, {} steps each; milliseconds of thread time per step, "
                   "summed over the threads; the integration's last instructions may be charged to the phase "
                   "after it)\n", table, integratorName(integrator), steps);
    return kExitSuccess;
}

/// The rows, the cloth's, the piles' and fountain-1m's as {"results": [...]}.
void printJson(const std::vector<Row>& rows, const std::vector<ClothRow>& cloth, const std::vector<PileRun>& piles,
               const std::vector<GranularRow>& grains, const SceneRun& fountain, int cores)
{
    nlohmann::json out;
    out["results"] = nlohmann::json::array();
    for (const Row& r : rows)
        out["results"].push_back({{"layout", r.layout}, {"integrator", r.integrator}, {"phase", r.phase}, {"n", r.n},
                                  {"threads", r.threads}, {"particle_steps_per_s", r.rate},
                                  {"particle_steps_per_s_median", r.medianRate},
                                  {"bytes_per_particle", r.bytesPerParticle}, {"fraction_of_bound", r.ofBound},
                                  {"times_baseline", r.ofBaseline}});
    const SpanRun& scene = fountain.run;
    const double sceneRate = scene.stepsPerSecond * double(fountain.n); // the slowest span's
    out["results"].push_back({{"layout", "scene"}, {"scene", "fountain-1m"}, {"integrator", fountain.integrator},
                              {"n", fountain.n}, {"threads", scene.threads}, {"particle_steps_per_s", sceneRate},
                              {"particle_steps_per_s_median", sceneRate}, {"bytes_per_particle", 0.0},
                              {"steps_per_s", scene.stepsPerSecond},
                              {"steps_per_s_overall", scene.overallStepsPerSecond}, {"spans", scene.spans},
                              {"steps_per_span", scene.spanSteps}, {"slowest_span_from_s", scene.slowestFrom}});
    for (const ClothRow& c : cloth) {
        nlohmann::json row{{"layout", "cloth"}, {"scene", "cloth-in-the-dryer"},
                           {"integrator", std::string(integratorName(c.integrator))}, {"dt", c.dt},
                           {"n", c.particles}, {"springs", c.springs}, {"threads", c.threads},
                           {"steps_per_s", c.stepsPerSecond}, {"steps_per_s_median", c.medianStepsPerSecond}};
        if (c.integrator == Integrator::SemiImplicitEuler)
            row["spring_evaluations_per_s"] = c.stepsPerSecond * double(c.springs);
        if (c.integrator == Integrator::ImplicitEuler)
            row["cg_iterations"] = c.iterations;
        if (c.integrator == Integrator::Xpbd)
            row["substeps"] = c.substeps;
        out["results"].push_back(row);
    }
    for (const PileRun& pile : piles) {
        const SpanRun& run = pile.run;
        out["results"].push_back({{"layout", "pile"}, {"scene", "dice"}, {"integrator", "semi-implicit-euler"},
                                  {"n", pile.dice}, {"threads", run.threads}, {"steps_per_s", run.stepsPerSecond},
                                  {"steps_per_s_overall", run.overallStepsPerSecond}, {"spans", run.spans},
                                  {"steps_per_span", run.spanSteps}, {"slowest_span_from_s", run.slowestFrom}});
    }
    for (const GranularRow& g : grains)
        out["results"].push_back({{"layout", "granular"}, {"scene", "granular"}, {"n", g.n}, {"threads", g.threads},
                                  {"particle_steps_per_s", g.rate}, {"without_collisions", g.withoutCollisions},
                                  {"particle_steps_per_s_median", g.medianRate},
                                  {"without_collisions_median", g.medianWithout}});
    out["machine"] = {{"cores", cores}};
    fmt::print("{}\n", out.dump(2));
}

/// The same as tables, each scene row with its target.
void printTables(const std::vector<Row>& rows, const std::vector<ClothRow>& cloth, const std::vector<PileRun>& piles,
                 const std::vector<GranularRow>& grains, const SceneRun& fountain)
{
    fmt::print("{}{}", table(rows), spreadNotes(rows));
    fmt::print("\n{:<7} {:<20} {:>8} {:>9} {:>9} {:>7} {:>9} {:>9}  {}\n", "layout", "integrator", "dt (s)",
               "particles", "springs", "threads", "steps/s", "median", "a step");
    for (const ClothRow& c : cloth) {
        const std::string cost = c.integrator == Integrator::ImplicitEuler ? fmt::format("{} CG iterations", c.iterations)
                                 : c.integrator == Integrator::Xpbd       ? fmt::format("{} substeps", c.substeps)
                                                                          : std::string("one force evaluation");
        fmt::print("{:<7} {:<20} {:>8.4g} {:>9} {:>9} {:>7} {:>9.0f} {:>9.0f}  {}\n", "cloth", integratorName(c.integrator),
                   c.dt, c.particles, c.springs, c.threads, c.stepsPerSecond, c.medianStepsPerSecond, cost);
    }
    fmt::print("(cloth-in-the-dryer at {} x {}, springs and dryer scaled with the particles' mass: gravity, the dryer "
               "and the room; targets on all cores: semi-implicit Euler 1,000 steps/s at dt 0.002, implicit-euler and "
               "xpbd 60 steps/s at dt 1/60, real time with one step a frame)\n",
               kClothSide, kClothSide);
    fmt::print("\n{:<7} {:>6} {:>7} {:>16} {:>10} {:>12}  {}\n", "layout", "dice", "threads", "slowest steps/s",
               "from t (s)", "over run", "target (bench/peers/pile.py measures Bullet's rate beside it)");
    for (const PileRun& pile : piles) {
        const SpanRun& run = pile.run;
        const char* target = pile.dice == 1000    ? "200 steps/s, and 5 times Bullet's"
                             : pile.dice == 10000 ? "10 times Bullet's"
                                                  : "";
        fmt::print("{:<7} {:>6} {:>7} {:>16.0f} {:>10.3g} {:>12.0f}  {}\n", "pile", pile.dice, run.threads,
                   run.stepsPerSecond, run.slowestFrom, run.overallStepsPerSecond, target);
    }
    fmt::print("(manyDice's 10 cm dice thrown into the dice scene's room, semi-implicit Euler with contacts, {} spans "
               "of {} steps from the throw: the slowest span's physics steps per second, and the whole run's)\n",
               piles.front().run.spans, piles.front().run.spanSteps);
    fmt::print("\n{:<9} {:>8} {:>7} {:>16} {:>10} {:>18} {:>10} {:>9}\n", "layout", "N", "threads",
               "particle-steps/s", "median", "without collisions", "median", "fraction");
    for (const GranularRow& g : grains)
        fmt::print("{:<9} {:>8} {:>7} {:>16.3e} {:>10.3e} {:>18.3e} {:>10.3e} {:>9.2f}\n", "granular", g.n, g.threads,
                   g.rate, g.medianRate, g.withoutCollisions, g.medianWithout, g.rate / g.withoutCollisions);
    fmt::print("(the granular scene's grains, 5 mm, in a sparse layer falling onto a floor sized to them, from their "
               "10th step; windows of the swarm with its contacts and without them taken in turn; target: a fraction "
               "of 0.2 or more)\n");
    const SpanRun& scene = fountain.run;
    fmt::print("\nfountain-1m ({} particles, {} threads, {} spans of {} steps): {:.0f} physics steps/s in its "
               "slowest span (from t = {:.3g} s), {:.0f} over the whole run (real time needs 480: 8 steps a 60 Hz "
               "frame; issue 24's target is 1,800 in the slowest span)\n",
               fountain.n, scene.threads, scene.spans, scene.spanSteps, scene.stepsPerSecond, scene.slowestFrom,
               scene.overallStepsPerSecond);
}

int runBench(const BenchOptions& options)
{
    if (options.integratorGiven && !options.peerWorker && !options.phases)
        throw UsageError("--integrator: only with --phases or --peer-worker (the rows time every integrator)");
    if (options.peerWorker)
        return runPeerWorker(options);
    if (options.pileWorker && options.dice < 1)
        throw UsageError(fmt::format("--dice: must be a whole number of at least 1, got {}", options.dice));
    if (options.pileWorker)
        return runPileWorker(static_cast<std::size_t>(options.dice), options.iterations);
    if (options.phases)
        return runPhases(options);
    std::vector<std::size_t> sizes;
    for (double s : options.sizes.empty() ? std::vector<double>{1e3, 1e5, 1e6, 1e7} : options.sizes) {
        // A swarm of the scene's particles: a whole number of them, at least one, at most what
        // the scene format allows.
        if (!(s >= 1.0 && s <= 1e8 && s == std::floor(s)))
            throw UsageError(fmt::format("--sizes: each size must be a whole number from 1 to 1e8, got {}", s));
        sizes.push_back(static_cast<std::size_t>(s));
    }
    if (options.quick && options.sizes.empty())
        sizes = {1000, 100000};
    const double minTime = options.quick ? 0.02 : 0.25;
    const int repeats = options.windows > 0 ? options.windows : options.quick ? 1 : 6;
    const int cores = machineCores();
    std::vector<Row> rows;
    const std::size_t largest = *std::max_element(sizes.begin(), sizes.end());
    const double memory = largest >= 1000000 ? bytesPerParticle(largest) : 0.0;
    for (std::size_t n : sizes) {
        const std::vector<Row> measured = measureSize(n, minTime, repeats, cores, n == largest ? memory : 0.0);
        rows.insert(rows.end(), measured.begin(), measured.end());
        if (!options.json)
            fmt::print(stderr, "measured N = {}\n", n);
    }
    if (!options.json)
        fmt::print(stderr, "stepping a {} x {} cloth\n", kClothSide, kClothSide);
    const std::vector<ClothRow> cloth = measureCloth(minTime, repeats, cores);
    std::vector<PileRun> piles;
    for (const std::size_t dice : kPileDice) {
        if (!options.json)
            fmt::print(stderr, "throwing {} dice\n", dice);
        piles.push_back(runPile(dice, options.quick, cores));
    }
    if (!options.json)
        fmt::print(stderr, "pouring grains\n");
    const std::vector<GranularRow> grains = measureGranular(options.quick, minTime, repeats, cores);
    if (!options.json)
        fmt::print(stderr, "stepping fountain-1m {}\n",
                   options.quick ? "for two spans of 4 steps" : "through its whole duration");
    const SceneRun fountain = runScene(options.quick, cores);
    if (options.json)
        printJson(rows, cloth, piles, grains, fountain, cores);
    else
        printTables(rows, cloth, piles, grains, fountain);
    return kExitSuccess;
}

} // namespace

void addBenchCommand(CLI::App& root, Action& selected)
{
    auto options = std::make_shared<BenchOptions>();
    CLI::App* bench = root.add_subcommand("bench", "Measure particle-steps per second: swarms with each integrator "
                                                   "on 1 and all cores, the heap-Particle baseline, the bandwidth "
                                                   "bound, a 128 x 128 cloth, piles of 1,000 and 10,000 "
                                                   "dice");
    bench->add_flag("--json", options->json,
                    "Print one JSON object instead of the tables: {\"machine\": {\"cores\": N}, \"results\": [...]}, "
                    "a row of each table an object with its \"layout\" (with --phases {\"results\": [...]} alone; "
                    "the keys: docs/commands.md)");
    bench->add_flag("--quick", options->quick, "Measure briefly, at N = 1e3 and 1e5 (for scripted checks)");
    bench->add_option("--windows", options->windows, "Windows timed per row, 1 to 100 (default 6, 1 with --quick)")
        ->transform(decimalOnly())
        ->check(CLI::Range(1, 100))
        ->option_text("N");
    bench->add_option("--sizes", options->sizeList, "Comma-separated particle counts (default 1e3,1e5,1e6,1e7)")
        ->option_text("N,...");
    CLI::Option* peerWorker = bench->add_flag("--peer-worker", options->peerWorker,
                    "For bench/peers/run.py and bench/alternate.py: only the swarm (semi-implicit Euler, or "
                    "--integrator's) on all cores at the one size of --sizes, its windows taken on request from "
                    "standard input (see bench/peers/run.py); not with --phases");
    bench->add_flag("--phases", options->phases,
                    "Instead of the rows: where a swarm step's time goes (integrate, surface test, collide, check), "
                    "in flight, landed and rested, at the sizes of --sizes (default 1e6); not with --peer-worker")
        ->excludes(peerWorker);
    CLI::Option* integrator = bench->add_option("--integrator", options->integrator,
                      "With --phases or --peer-worker: the swarm's integrator, forward-euler, semi-implicit-euler "
                      "(default), velocity-verlet or rk4")
        ->option_text("NAME");
    bench->add_option("--phase", options->phase,
                      "With --peer-worker: flight (from t = 0), landed (from t = 2 s) or rested (from t = 8 s)")
        ->check(CLI::IsMember({"flight", "landed", "rested"}))
        ->needs(peerWorker)
        ->option_text("PHASE");
    CLI::Option* pileWorker = bench->add_flag("--pile-worker", options->pileWorker,
                    "For bench/peers/pile.py: only a pile of --dice dice (manyDice's throw) on all cores, its "
                    "windows taken on request from standard input and its state saved as CSV (see "
                    "bench/peers/README.md); not with --peer-worker or --phases")
                    ->excludes(peerWorker);
    bench->get_option("--phases")->excludes(pileWorker);
    bench->add_option("--dice", options->dice, "With --pile-worker: the dice thrown (default 1000)")
        ->transform(decimalOnly())
        ->needs(pileWorker)
        ->option_text("N");
    bench->add_option("--iterations", options->iterations,
                      "With --pile-worker: the solver's velocity sweeps a step, a fixed count (default 10, Bullet's)")
        ->transform(decimalOnly())
        ->needs(pileWorker)
        ->check(CLI::Range(1, 1000))
        ->option_text("N");
    bench->footer("The workload is the blow-dryer-swarm scene (gravity, the blow dryer, the room's walls and the\n"
                  "hole) at dt = 0.002, each swarm row in three phases: in flight, from the scene's first state\n"
                  "(the rain falling, a quarter of it in the dryer's cone); landed, from its state at t = 2 s\n"
                  "(the rain after its first bounce, a few particles of each block at the floor in any step);\n"
                  "rested, from its state at t = 8 s (nearly all of it on the floor, where the collision code\n"
                  "runs for every particle every step). The baseline is timed in flight only. Each row of a\n"
                  "size is timed in 6 windows (--windows; one with --quick), each the same work: from the\n"
                  "row's start state, as many steps as filled a first quarter second (0.02 s with --quick).\n"
                  "The rows take their windows in turn so that a machine's drifting speed slows them alike.\n"
                  "Every rate, the bound's and each row's, is its best window (a slower one is other work on\n"
                  "the machine getting in the way), so the ratios compare best with best; the median window\n"
                  "is printed beside it. Compare rows of one run, not across runs.\n"
                  "Then the cloth rows: cloth-in-the-dryer with a 128 x 128 sheet (16,384 particles and 97,026\n"
                  "springs, their stiffness and damping and the dryer's strength scaled with the particles' mass\n"
                  "so that each moves as in the 10 x 10 built-in), semi-implicit Euler at dt = 0.002 and\n"
                  "implicit-euler and xpbd at dt = 1/60 (a frame), each on 1 thread and on all cores, windows\n"
                  "as above: physics steps per second, and what a step cost (a force evaluation, the conjugate\n"
                  "gradients' iterations, xpbd's substeps). Its states are the same on any number of threads.\n"
                  "Then the pile rows: 1,000 and 10,000 rigid 10 cm boxes thrown into the dice scene's room\n"
                  "(manyDice: from cells of a lattice over the room, none overlapping another), semi-implicit\n"
                  "Euler with contacts on all cores, stepped from the throw through the landing to rest (4 s;\n"
                  "two spans of 10 steps with --quick), timed half a second at a time: physics steps per second\n"
                  "in the slowest half second and over the run. Their states are the same on any number of\n"
                  "threads. bench/peers/pile.py times the same throws beside Bullet's.\n"
                  "Then the granular rows: the granular scene's grains (5 mm) at 1e5 and 1e6 (1e5 only with\n"
                  "--quick), a sparse layer falling onto a floor sized to them, from its 10th step, on all cores,\n"
                  "with their contacts and without them, windows taken in turn as above.\n"
                  "Last, the fountain-1m scene is stepped as a program would through its whole 10 s, timed a\n"
                  "simulated second at a time (two spans of 4 steps with --quick); its physics steps per second\n"
                  "are reported for its slowest second (the one a real-time program must keep up with) and for\n"
                  "the whole run.\n"
                  "\nWith --phases it prints instead where a swarm step's time goes: the semi-implicit Euler\n"
                  "swarm (or --integrator's) on all cores, in flight, landed and rested, from the same\n"
                  "start states whatever the integrator, at the sizes of --sizes (default 1e6),\n"
                  "200 steps each (10 with --quick), in milliseconds of thread time a step for each phase\n"
                  "(integrate, surface test, collide, check; timing them slows a step a little). The clock\n"
                  "is read without waiting for a phase to finish, so some of the integration's time shows\n"
                  "up in the phase after it: the surface test's, or at rest the collision's (see docs/swarms.md).\n"
                  "\nExamples:\n  pba bench --quick\n  pba bench --quick --json\n"
                  "  pba bench --phases --sizes 1e5 --quick\n");
    bench->callback([options, integrator, &selected] {
        options->integratorGiven = integrator->count() > 0;
        selected = [options] {
            BenchOptions read = *options;
            read.sizes = numberList("--sizes", read.sizeList);
            return runBench(read);
        };
    });
}

} // namespace pba::app
