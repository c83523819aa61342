// `pba bench`: particle-steps per second of the swarm layout against the practical's
// vector of heap Particles and against the memory-bandwidth bound, measured in one run.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string_view>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "command.hpp"
#include "scene_options.hpp"
#include "pba/blow_dryer.hpp"
#include "pba/large_array.hpp"
#include "pba/scene/scene.hpp"
#include "pba/spring_network.hpp"

namespace pba::app {

namespace {

using Clock = std::chrono::steady_clock;

struct BenchOptions {
    bool json = false;
    bool quick = false;
    int windows = 0; ///< 0: the default (6, one with --quick)
    std::vector<double> sizes;
    bool peerWorker = false; ///< --peer-worker: one row, windows on request (bench/peers/run.py)
    std::string phase = "flight";
    bool phases = false; ///< --phases: where a swarm step's time goes, instead of the rows
    std::string integrator = "semi-implicit-euler"; ///< --phases' integrator
};

struct Row {
    std::string layout;
    std::string integrator;
    std::string phase; ///< "flight" or "landed" for the swarm and the baseline, empty for the bound
    std::size_t n = 0;
    int threads = 1;
    double rate = 0.0; ///< particle-steps per second: the best window (see measureSize)
    double bytesPerParticle = 0.0;
    double ofBound = 0.0;
    double ofBaseline = 0.0;
    double stepsPerSecond = 0.0; ///< physics steps per second (the scene row only)
    double medianRate = 0.0;     ///< the median window, for how far the machine's speed swung
};

/// The states of blow-dryer-swarm a swarm row's windows start from, and the times the scene
/// reaches them. In flight: its first state, the rain falling (a quarter of it in the dryer's
/// cone). Landed, at 2 s: the rain after its first bounce (mean height 0.4 m, under 1% within
/// 10 cm of the floor in any step: few particles a block meet a surface), some in the jet and
/// the hole. Rested, at 8 s: nearly all of it on the floor (mean height 2 mm, 99.8% within
/// 1 cm; fountain-1m's state from about 4 s to its end), where the collision code runs for
/// every particle every step. (Measured at 1e5 particles, 2026-11-26.)
struct Phase {
    const char* name;
    double time;
};
constexpr std::array<Phase, 3> kPhases{{{"flight", 0.0}, {"landed", 2.0}, {"rested", 8.0}}};

double seconds(Clock::time_point from) { return std::chrono::duration<double>(Clock::now() - from).count(); }

/// Runs `step` until minTime has passed; how many times it ran.
long stepsIn(double minTime, const std::function<void()>& step)
{
    const auto start = Clock::now();
    long steps = 0;
    do {
        step();
        ++steps;
    } while (seconds(start) < minTime);
    return steps;
}

/// Runs `step` `steps` times; the rate, in particle-steps per second.
double timedRate(std::size_t n, long steps, const std::function<void()>& step)
{
    const auto start = Clock::now();
    for (long k = 0; k < steps; ++k)
        step();
    return double(n) * double(steps) / seconds(start);
}

/// The median of a few rates.
double median(std::vector<double> rates)
{
    std::sort(rates.begin(), rates.end());
    return rates[rates.size() / 2];
}

/// The best of a few rates.
double best(const std::vector<double>& rates) { return *std::max_element(rates.begin(), rates.end()); }

/// One row of a size: the step it times and how to restart it (both own its worlds), the steps
/// in each of its windows and their rates.
struct Subject {
    Row row;
    std::function<void()> step;
    std::function<void()> restart;
    long steps = 0;
    std::vector<double> rates;
};

/// Times the subjects' windows in turn, round after round (measureSize says why): each first
/// takes as many steps as fill minTime, then every window restarts it and takes that many.
template <class S>
void timeInTurn(std::vector<S>& subjects, std::size_t perStep, double minTime, int repeats)
{
    for (S& subject : subjects) {
        subject.step(); // warm caches and page in memory
        subject.steps = stepsIn(minTime, subject.step);
    }
    for (int r = 0; r < repeats; ++r)
        for (S& subject : subjects) {
            subject.restart();
            subject.rates.push_back(timedRate(perStep, subject.steps, subject.step));
        }
}

/// A world that a subject steps, and restarts from where it began.
struct Restartable {
    std::function<void()> step, restart;
};

Restartable restartable(World world)
{
    auto first = std::make_shared<const World>(std::move(world));
    auto current = std::make_shared<World>(*first);
    return {[current] { current->step(0.002); }, [current, first] { *current = *first; }};
}

/// The blow-dryer-swarm scene's world with n particles of the given integrator.
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

/// The start states of kPhases up to phase `last`: swarmWorld's semi-implicit Euler swarm stepped
/// to each phase's time (each row sets its own integrator and threads on a copy).
std::vector<World> phaseWorlds(std::size_t n, std::size_t last = kPhases.size() - 1)
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

/// The phase named `name` (one of kPhases), its index.
std::optional<std::size_t> phaseIndex(std::string_view name)
{
    for (std::size_t p = 0; p < kPhases.size(); ++p)
        if (name == kPhases[p].name)
            return p;
    return std::nullopt;
}

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

/// fountain-1m as a program runs it: its physics steps per second in its slowest span and
/// over the whole run.
struct SceneRun {
    Row row; ///< rate and stepsPerSecond: the slowest span's
    double overallStepsPerSecond = 0.0;
    int spans = 0, spanSteps = 0;
};

/// A world stepped as a program steps it, `spans` spans of `spanSteps` steps, each timed: the
/// slowest span's steps per second, and the seconds of the whole run.
struct SpanTimes {
    double slowest = 0.0, total = 0.0;
};

SpanTimes timeSpans(World& world, double dt, int spans, int spanSteps)
{
    SpanTimes t{std::numeric_limits<double>::infinity(), 0.0};
    for (int span = 0; span < spans; ++span) {
        const auto start = Clock::now();
        for (int k = 0; k < spanSteps; ++k)
            world.step(dt);
        const double elapsed = seconds(start);
        t.slowest = std::min(t.slowest, spanSteps / elapsed);
        t.total += elapsed;
    }
    return t;
}

/// fountain-1m as a program runs it: a million particles, all cores, steps of the scene's dt
/// over its whole duration, timed a simulated second at a time (--quick: two spans of 4 steps).
/// The rain in flight is the cheap part; from about 4 s nearly every particle lies on the floor,
/// bouncing in place within the contact tolerance, and some slide around the hole's shaft: the
/// collision code runs for all of them every step, and the last second is the slowest. A
/// program must keep up with its slowest second, so that is the row's rate; the whole run's
/// average is beside it.
SceneRun runScene(bool quick)
{
    Scene scene = loadScene("fountain-1m");
    World& world = scene.world;
    world.setThreads(0);
    SceneRun run;
    run.spanSteps = quick ? 4 : static_cast<int>(std::lround(1.0 / scene.dt));
    run.spans = quick ? 2 : static_cast<int>(std::lround(scene.duration));
    const auto [slowest, total] = timeSpans(world, scene.dt, run.spans, run.spanSteps);
    const std::size_t n = world.swarm(0).size();
    const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    run.row = Row{"scene", std::string(integratorName(world.swarm(0).integrator())), "", n, cores, slowest * double(n),
                  0.0, 0.0, 0.0};
    run.row.stepsPerSecond = slowest;
    run.row.medianRate = run.row.rate;
    run.overallStepsPerSecond = double(run.spans) * run.spanSteps / total;
    return run;
}

/// The dice row: kDice 10 cm dice (manyDice) thrown into the dice scene's room, semi-implicit
/// Euler with contacts on all cores, stepped as a program would from the throw through their
/// landing (bounces, slides, new contacts every step: the solver's hardest time) to rest, timed
/// half a simulated second at a time; the row's rate is its slowest span (a program must keep up
/// with it), the whole run's beside it. (--quick: two spans of 10 steps, in flight.)
constexpr std::size_t kDice = 10000;
constexpr double kDiceDuration = 4.0;

struct DiceRun {
    int threads = 1;
    double stepsPerSecond = 0.0, overallStepsPerSecond = 0.0;
    int spans = 0, spanSteps = 0;
};

DiceRun runDice(bool quick, int cores)
{
    Scene scene = manyDice(kDice);
    World& world = scene.world;
    world.setThreads(0);
    DiceRun run;
    run.threads = cores;
    run.spanSteps = quick ? 10 : static_cast<int>(std::lround(0.5 / scene.dt));
    run.spans = quick ? 2 : static_cast<int>(std::lround(kDiceDuration / 0.5));
    const auto [slowest, total] = timeSpans(world, scene.dt, run.spans, run.spanSteps);
    run.stepsPerSecond = slowest;
    run.overallStepsPerSecond = double(run.spans) * run.spanSteps / total;
    return run;
}

/// The cloth row's side: 128 x 128 particles, 97,026 springs.
constexpr int kClothSide = 128;

/// cloth-in-the-dryer at kClothSide x kClothSide (resizedClothInTheDryer): one system of springs
/// (structural, shear and bending), semi-implicit Euler, gravity, the blow dryer and the room.
World clothWorld(int threads)
{
    World world = resizedClothInTheDryer(kClothSide).world;
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

/// A cloth row: its physics steps per second (best window) and the spring evaluations they make
/// (semi-implicit Euler evaluates each spring once a step).
struct ClothRow {
    int threads = 1;
    std::size_t particles = 0, springs = 0;
    double stepsPerSecond = 0.0, medianStepsPerSecond = 0.0;
};

/// The cloth on 1 thread and on all cores, their windows taken in turn (as measureSize's), each
/// window the same work: from the scene's first state (the sheet falling flat toward the jet),
/// as many steps as filled a first window.
std::vector<ClothRow> measureCloth(double minTime, int repeats, int cores)
{
    struct ClothSubject {
        ClothRow row;
        std::function<void()> step, restart;
        long steps = 0;
        std::vector<double> rates;
    };
    std::vector<ClothSubject> subjects;
    for (int threads : {1, cores}) {
        World world = clothWorld(threads);
        const ClothRow row{threads, world.bodyCount(), springCount(world), 0.0, 0.0};
        Restartable r = restartable(std::move(world));
        subjects.push_back({row, std::move(r.step), std::move(r.restart), 0, {}});
        if (threads == cores)
            break;
    }
    timeInTurn(subjects, 1, minTime, repeats);
    std::vector<ClothRow> rows;
    for (ClothSubject& s : subjects) {
        s.row.stepsPerSecond = best(s.rates);
        s.row.medianStepsPerSecond = median(s.rates);
        rows.push_back(s.row);
    }
    return rows;
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

/// Peak memory per swarm particle: measured first, before anything else has raised the peak,
/// as the growth of the peak while an n-particle swarm world is built and stepped.
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

std::string table(const std::vector<Row>& rows)
{
    std::string out = fmt::format("{:<9} {:<20} {:<7} {:>9} {:>7} {:>16} {:>10} {:>9} {:>11} {:>12}\n", "layout",
                                  "integrator", "phase", "N", "threads", "particle-steps/s", "median", "of bound",
                                  "x baseline", "bytes/part.");
    for (const Row& r : rows)
        out += fmt::format("{:<9} {:<20} {:<7} {:>9} {:>7} {:>16.3e} {:>10.3e} {:>9} {:>11} {:>12}\n", r.layout,
                           r.integrator, r.phase, r.n, r.threads, r.rate, r.medianRate,
                           r.ofBound > 0 ? fmt::format("{:.2f}", r.ofBound) : "",
                           r.ofBaseline > 0 ? fmt::format("{:.1f}", r.ofBaseline) : "",
                           r.bytesPerParticle > 0 ? fmt::format("{:.1f}", r.bytesPerParticle) : "");
    return out;
}

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

/// `pba bench --peer-worker`: the semi-implicit Euler swarm of blow-dryer-swarm on all cores, at
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
    const auto n = static_cast<std::size_t>(size);
    const double startTime = kPhases[*phase].time;
    const World first = std::move(phaseWorlds(n, *phase).back());
    World world = first;
    double t = startTime;
    const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    fmt::print("{}\n", nlohmann::json{{"ready", true}, {"n", n}, {"phase", options.phase}, {"t", t},
                                      {"threads", cores}}.dump());
    std::fflush(stdout);
    for (std::string line; std::getline(std::cin, line);) {
        std::istringstream words(line);
        std::string command;
        words >> command;
        nlohmann::json answer;
        if (command == "window") {
            long steps = 0;
            if (!(words >> steps) || steps < 1)
                throw UsageError(fmt::format("--peer-worker: 'window STEPS' with STEPS >= 1, got '{}'", line));
            world = first;
            const auto start = Clock::now();
            for (long k = 0; k < steps; ++k)
                world.step(0.002);
            const double elapsed = seconds(start);
            t = startTime + 0.002 * double(steps);
            answer = {{"seconds", elapsed}, {"steps", steps}, {"t", t},
                      {"particle_steps_per_s", double(n) * double(steps) / elapsed}};
        } else if (command == "stats") {
            answer = swarmStatistics(world, t);
        } else if (command.empty()) {
            continue;
        } else {
            throw UsageError(fmt::format("--peer-worker: unknown command '{}' (window STEPS, stats)", line));
        }
        fmt::print("{}\n", answer.dump());
        std::fflush(stdout);
    }
    return kExitSuccess;
}

/// --phases: the swarm on all cores with --integrator (semi-implicit Euler unless told), in each
/// of kPhases (the same start states whatever the integrator), each step's time split by phase
/// (SwarmPhaseTimes: thread-time summed over the threads, so on 2 threads the phases add up to
/// about twice the step's wall time).
int runPhases(const BenchOptions& options)
{
    const std::vector<double> sizes = options.sizes.empty() ? std::vector<double>{1e6} : options.sizes;
    const Integrator integrator = integratorFlag(options.integrator);
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
                   "summed over the threads)\n", table, integratorName(integrator), steps);
    return kExitSuccess;
}

int runBench(const BenchOptions& options)
{
    if (options.peerWorker)
        return runPeerWorker(options);
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
    const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
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
    if (!options.json)
        fmt::print(stderr, "throwing {} dice\n", kDice);
    const DiceRun dice = runDice(options.quick, cores);
    if (!options.json)
        fmt::print(stderr, "stepping fountain-1m through its whole duration\n");
    const SceneRun fountain = runScene(options.quick);
    const Row& scene = fountain.row;
    if (options.json) {
        nlohmann::json out;
        out["results"] = nlohmann::json::array();
        for (const Row& r : rows)
            out["results"].push_back({{"layout", r.layout}, {"integrator", r.integrator}, {"phase", r.phase}, {"n", r.n},
                                      {"threads", r.threads}, {"particle_steps_per_s", r.rate},
                                      {"particle_steps_per_s_median", r.medianRate},
                                      {"bytes_per_particle", r.bytesPerParticle}, {"fraction_of_bound", r.ofBound},
                                      {"times_baseline", r.ofBaseline}});
        out["results"].push_back({{"layout", "scene"}, {"scene", "fountain-1m"}, {"integrator", scene.integrator},
                                  {"n", scene.n}, {"threads", scene.threads},
                                  {"particle_steps_per_s", scene.rate},
                                  {"particle_steps_per_s_median", scene.medianRate}, {"bytes_per_particle", 0.0},
                                  {"steps_per_s", scene.stepsPerSecond},
                                  {"steps_per_s_overall", fountain.overallStepsPerSecond},
                                  {"spans", fountain.spans}, {"steps_per_span", fountain.spanSteps}});
        for (const ClothRow& c : cloth)
            out["results"].push_back({{"layout", "cloth"}, {"scene", "cloth-in-the-dryer"},
                                      {"integrator", "semi-implicit-euler"}, {"n", c.particles},
                                      {"springs", c.springs}, {"threads", c.threads},
                                      {"steps_per_s", c.stepsPerSecond},
                                      {"steps_per_s_median", c.medianStepsPerSecond},
                                      {"spring_evaluations_per_s", c.stepsPerSecond * double(c.springs)}});
        out["results"].push_back({{"layout", "dice"}, {"scene", "dice"}, {"integrator", "semi-implicit-euler"},
                                  {"n", kDice}, {"threads", dice.threads}, {"steps_per_s", dice.stepsPerSecond},
                                  {"steps_per_s_overall", dice.overallStepsPerSecond}, {"spans", dice.spans},
                                  {"steps_per_span", dice.spanSteps}});
        out["machine"] = {{"cores", cores}};
        fmt::print("{}\n", out.dump(2));
    } else {
        fmt::print("{}", table(rows));
        fmt::print("\n{:<7} {:>9} {:>9} {:>7} {:>12} {:>10} {:>20}\n", "layout", "particles", "springs", "threads",
                   "steps/s", "median", "spring evaluations/s");
        for (const ClothRow& c : cloth)
            fmt::print("{:<7} {:>9} {:>9} {:>7} {:>12.0f} {:>10.0f} {:>20.3e}\n", "cloth", c.particles, c.springs,
                       c.threads, c.stepsPerSecond, c.medianStepsPerSecond, c.stepsPerSecond * double(c.springs));
        fmt::print("(cloth-in-the-dryer at {} x {}, springs and dryer scaled with the particles' mass: "
                   "semi-implicit Euler, gravity, the dryer and the room; target 1,000 steps/s on all cores)\n",
                   kClothSide, kClothSide);
        fmt::print("\ndice ({} rigid boxes, {} threads, {} spans of {} steps from the throw): {:.0f} physics steps/s in "
                   "the slowest span, {:.0f} over the whole run (target 200)\n",
                   kDice, dice.threads, dice.spans, dice.spanSteps, dice.stepsPerSecond, dice.overallStepsPerSecond);
        fmt::print("\nfountain-1m ({} particles, {} threads, {} spans of {} steps): {:.0f} physics steps/s in its "
                   "slowest span, {:.0f} over the whole run (real time needs 480: 8 steps a 60 Hz frame; "
                   "issue 24's target is 1,800 in the slowest span)\n",
                   scene.n, scene.threads, fountain.spans, fountain.spanSteps, scene.stepsPerSecond,
                   fountain.overallStepsPerSecond);
    }
    return kExitSuccess;
}

} // namespace

void addBenchCommand(CLI::App& root, Action& selected)
{
    auto options = std::make_shared<BenchOptions>();
    CLI::App* bench = root.add_subcommand("bench", "Measure particle-steps per second: swarms with each integrator "
                                                   "on 1 and all cores, the heap-Particle baseline, the bandwidth "
                                                   "bound, a 128 x 128 cloth, 10,000 dice");
    bench->add_flag("--json", options->json, "Print {\"results\": [...]} instead of a table");
    bench->add_flag("--quick", options->quick, "Measure briefly, at N = 1e3 and 1e5 (for scripted checks)");
    bench->add_option("--windows", options->windows, "Windows timed per row, 1 to 100 (default 6, 1 with --quick)")
        ->check(CLI::Range(1, 100))
        ->option_text("N");
    bench->add_option("--sizes", options->sizes, "Comma-separated particle counts (default 1e3,1e5,1e6,1e7)")
        ->delimiter(',')
        ->option_text("N,...");
    CLI::Option* peerWorker = bench->add_flag("--peer-worker", options->peerWorker,
                    "For bench/peers/run.py: only the semi-implicit Euler swarm on all cores at the one size "
                    "of --sizes, its windows taken on request from standard input (see bench/peers/run.py)");
    CLI::Option* phases = bench->add_flag("--phases", options->phases,
                    "Instead of the rows: where a swarm step's time goes (integrate, surface test, collide, check), "
                    "in flight, landed and rested, at the sizes of --sizes (default 1e6)")
        ->excludes(peerWorker);
    bench->add_option("--integrator", options->integrator,
                      "With --phases: the swarm's integrator, any name pba sim's --integrator takes "
                      "(default semi-implicit-euler)")
        ->needs(phases)
        ->option_text("NAME");
    bench->add_option("--phase", options->phase,
                      "With --peer-worker: flight (from t = 0), landed (from t = 2 s) or rested (from t = 8 s)")
        ->check(CLI::IsMember({"flight", "landed", "rested"}))
        ->needs(peerWorker)
        ->option_text("PHASE");
    bench->footer("\nThe workload is the blow-dryer-swarm scene (gravity, the blow dryer, the room's walls and the\n"
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
                  "Then the cloth row: cloth-in-the-dryer with a 128 x 128 sheet (16,384 particles and 97,026\n"
                  "springs, their stiffness and damping and the dryer's strength scaled with the particles' mass\n"
                  "so that each moves as in the 10 x 10 built-in), semi-implicit Euler at dt = 0.002, on 1\n"
                  "thread and on all cores, windows as above: physics steps per second and spring evaluations\n"
                  "per second (one per spring a step). Its states are the same on any number of threads.\n"
                  "Then the dice row: 10,000 rigid 10 cm boxes thrown into the dice scene's room (they pass through\n"
                  "each other: rigid against rigid is not simulated), semi-implicit Euler with contacts on all\n"
                  "cores, stepped from the throw through the landing to rest (4 s), timed half a second at a\n"
                  "time: physics steps per second in the slowest half second and over the run. Its states are\n"
                  "the same on any number of threads.\n"
                  "Last, the fountain-1m scene is stepped as a program would through its whole 10 s, timed a\n"
                  "simulated second at a time (two spans of 4 steps with --quick); its physics steps per second\n"
                  "are reported for its slowest second (the one a real-time program must keep up with) and for\n"
                  "the whole run.\n"
                  "\nWith --phases it prints instead where a swarm step's time goes: the semi-implicit Euler\n"
                  "swarm (or --integrator's) on all cores, in flight, landed and rested, from the same\n"
                  "start states whatever the integrator, at the sizes of --sizes (default 1e6),\n"
                  "200 steps each (10 with --quick), in milliseconds of thread time a step for each phase\n"
                  "(integrate, surface test, collide, check; timing them slows a step a little).\n");
    bench->callback([options, &selected] { selected = [options] { return runBench(*options); }; });
}

} // namespace pba::app
