#include "clock_report.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "atomic_file.hpp"
#include "gnuplot.hpp"
#include "pba/clock.hpp"
#include "study/clock_plots.hpp"

namespace pba::app {

namespace {

const study::ClockRun& runOf(const study::ClockResult& result, ClockKind clock, bool hitch, int rate)
{
    return *std::find_if(result.runs.begin(), result.runs.end(), [&](const study::ClockRun& r) {
        return r.clock == clock && r.hitch == hitch && r.rate == rate;
    });
}

const study::ClockDrift& driftOf(const study::ClockResult& result, ClockKind clock, bool hitch, int rate)
{
    return *std::find_if(result.drifts.begin(), result.drifts.end(), [&](const study::ClockDrift& d) {
        return d.clock == clock && d.hitch == hitch && d.rate == rate;
    });
}

/// A drift as a cell: "identical", a distance, or which run blew up and when.
std::string cell(const study::ClockResult& result, const study::ClockDrift& d)
{
    if (d.identical)
        return "identical (to the bit)";
    const study::ClockRun& run = runOf(result, d.clock, d.hitch, d.rate);
    const study::ClockRun& reference = runOf(result, d.clock, d.hitch, study::kClockReferenceRate);
    if (!std::isnan(run.blewUpAt))
        return fmt::format("blew up at t = {:.4g} s", run.blewUpAt);
    if (!std::isnan(reference.blewUpAt))
        return fmt::format("(60 Hz blew up at t = {:.4g} s)", reference.blewUpAt);
    return fmt::format("{:.3g} m", d.maxDistance);
}

std::string frames(bool hitch)
{
    return hitch ? fmt::format("{:g} s hitch at {:g} s", study::kHitchSeconds, study::kHitchAt) : "steady";
}

bool allIdentical(const study::ClockResult& result, ClockKind clock)
{
    return std::all_of(result.drifts.begin(), result.drifts.end(),
                       [&](const study::ClockDrift& d) { return d.clock != clock || d.identical; });
}

/// The largest distance of a clock's runs from its 60 Hz runs, steady or through the hitch
/// (NaN if one blew up).
double largest(const study::ClockResult& result, ClockKind clock, bool hitch)
{
    double out = 0.0;
    for (const study::ClockDrift& d : result.drifts)
        if (d.clock == clock && d.hitch == hitch)
            out = std::isnan(d.maxDistance) || std::isnan(out) ? std::nan("") : std::max(out, d.maxDistance);
    return out;
}

std::string blowUps(const study::ClockResult& result, ClockKind clock)
{
    std::string out;
    for (const study::ClockRun& r : result.runs)
        if (r.clock == clock && !std::isnan(r.blewUpAt))
            out += fmt::format(" At {} Hz ({}) it blew up at t = {:.4g} s, its longest step {:.4g} s: {}.", r.rate,
                               frames(r.hitch), r.blewUpAt, r.longestStep, r.blowUp);
    return out;
}

std::string distanceText(double d)
{
    return std::isnan(d) ? std::string("cannot be measured past a blow-up") : fmt::format("reach {:.3g} m", d);
}

} // namespace

std::string clockTable(const study::ClockConfig& config, const study::ClockResult& result, bool markdown)
{
    (void)config;
    std::string out = markdown ? "| clock | frames | 30 Hz vs 60 Hz | 144 Hz vs 60 Hz | steps at 60 Hz | steps (s) |\n"
                                 "|---|---|---|---|---:|---|\n"
                               : fmt::format("{:<11} {:<22} {:<24} {:<24} {:>8}  {}\n", "clock", "frames", "30 Hz vs 60 Hz",
                                             "144 Hz vs 60 Hz", "steps", "step lengths (s)");
    for (const ClockKind clock : kClockKinds)
        for (const bool hitch : {false, true}) {
            const study::ClockRun& reference = runOf(result, clock, hitch, study::kClockReferenceRate);
            const std::string shortest = fmt::format("{:.4g}", reference.shortestStep);
            const std::string longest = fmt::format("{:.4g}", reference.longestStep);
            const std::string lengths = shortest == longest ? longest : shortest + " to " + longest;
            const std::string slow = cell(result, driftOf(result, clock, hitch, 30));
            const std::string fast = cell(result, driftOf(result, clock, hitch, 144));
            out += markdown ? fmt::format("| {} | {} | {} | {} | {} | {} |\n", clockName(clock), frames(hitch), slow, fast,
                                          reference.steps, lengths)
                            : fmt::format("{:<11} {:<22} {:<24} {:<24} {:>8}  {}\n", clockName(clock), frames(hitch),
                                          slow, fast, reference.steps, lengths);
        }
    return out;
}

std::string clockFindings(const study::ClockConfig& config, const study::ClockResult& result)
{
    std::string out;
    if (allIdentical(result, ClockKind::Fixed))
        out += fmt::format("- **fixed**: the runs at 30, 60 and 144 Hz are identical to the bit at every shared frame, "
                           "steady and through the hitch. The frame time only decides how many steps of dt = {:g} s "
                           "run now, never their length, so the physics is the same whatever the display does; the "
                           "{:g} s hitch is made up in whole steps in one frame (the clock clamps frames at {:g} s).\n",
                           config.dt, study::kHitchSeconds, FixedTimestepClock::kDefaultMaxFrameTime);
    else
        out += fmt::format("- **fixed**: the runs differ ({} steady, {} through the hitch): the steps of dt are the "
                           "same at every rate, so this is a defect of the clock or the study.\n",
                           distanceText(largest(result, ClockKind::Fixed, false)),
                           distanceText(largest(result, ClockKind::Fixed, true)));
    out += fmt::format("- **semi-fixed**: no step is longer than dt, so it is as stable as the fixed clock, but each "
                       "frame ends with a shorter step of what is left, different at every rate: the runs' distances "
                       "from the 60 Hz run {} steady and {} through the hitch.{}\n",
                       distanceText(largest(result, ClockKind::SemiFixed, false)),
                       distanceText(largest(result, ClockKind::SemiFixed, true)), blowUps(result, ClockKind::SemiFixed));
    const study::ClockRun& hitched = runOf(result, ClockKind::Variable, true, study::kClockReferenceRate);
    // A method exact for the scene (velocity Verlet on a bounce with exact impacts) follows one
    // trajectory at any dt: then the distances are rounding, and the text says so.
    const double variable = std::max(largest(result, ClockKind::Variable, false), largest(result, ClockKind::Variable, true));
    const char* which = variable < 1e-9 ? "another dt, though here not another trajectory, as the method follows "
                                          "this scene exactly at any dt: the distances, rounding,"
                                        : "another dt and another trajectory: the distances";
    out += fmt::format("- **variable**: every frame is one step of the frame's time, so every frame rate is {} {} "
                       "steady and {} through the hitch, where one step is {:.4g} s long ({:.3g} times dt).{}\n",
                       which,
                       distanceText(largest(result, ClockKind::Variable, false)),
                       distanceText(largest(result, ClockKind::Variable, true)), hitched.longestStep,
                       hitched.longestStep / config.dt, blowUps(result, ClockKind::Variable));
    return out;
}

void writeClockCsv(const std::filesystem::path& path, const study::ClockResult& result)
{
    AtomicFile file(path);
    auto& out = file.stream();
    out << "clock,hitch,rate,t,distance\n";
    for (const study::ClockDrift& d : result.drifts)
        for (std::size_t s = 0; s < d.t.size(); ++s)
            out << fmt::format("{},{},{},{},{}\n", clockName(d.clock), d.hitch ? 1 : 0, d.rate, d.t[s], d.distance[s]);
    file.commit();
}

bool writeClockPlot(const std::filesystem::path& dir, const study::ClockConfig& config, const study::ClockResult& result)
{
    if (!gnuplotAvailable())
        return false;
    ScratchDir scratch("pba-compare");
    runGnuplot(study::clockPlotScript(scratch.path(), config, result), scratch.path());
    publish(scratch.path() / study::kClockPlotFile, dir / study::kClockPlotFile);
    return true;
}

void writeClockReport(const std::filesystem::path& path, const study::ClockConfig& config,
                      const study::ClockResult& result, bool withPlot)
{
    AtomicFile file(path);
    auto& out = file.stream();
    out << fmt::format("# Clocks study: {}\n\n", config.scene.name);
    out << fmt::format(
        "Scene `{}`, {:g} s of wall-clock time at dt = {:g} s, driven by each clock at 30, 60 and 144 frames a second, "
        "steady and with one frame of {:g} s at t = {:g} s (a simulated stall). The runs at 30 and 144 Hz are compared "
        "with the run at 60 Hz of the same clock at the frames all three share (every 1/6 s): the largest distance of a "
        "moving body. `clocks.csv` holds every sample (clock, hitch, rate, t, distance in m).\n\n",
        config.scene.name, config.duration, config.dt, study::kHitchSeconds, study::kHitchAt);
    out << "## Findings\n\n" << clockFindings(config, result) << "\n";
    out << "## Distance from the 60 Hz run\n\n" << clockTable(config, result, true) << "\n";
    if (withPlot)
        out << "![clocks](clocks.png)\n\nEach line is a run's distance from its clock's 60 Hz run (30 Hz solid with "
               "circles, 144 Hz dashed with triangles) on a log axis; a run identical to the bit has no logarithm "
               "and is named in the panel's title instead.\n\n";
    else
        out << "(No plot: gnuplot is not installed; install the Debian package gnuplot-nox.)\n\n";
    out << "## The lesson\n\nA program that steps its physics by the frame time (`x += v * frame_time`) makes the "
           "simulation a function of the display: a faster monitor is a smaller dt and another trajectory, and a stall "
           "is one huge step, where a stiff spring or a fast body leaves the physics behind. Fiedler's semi-fixed step "
           "caps the step at dt, which keeps it stable, but still hands the physics the frame's remainder. The fixed "
           "clock gives the physics only whole steps of dt and draws the remainder by interpolating the last two "
           "states (alpha = accumulator / dt), so the same scene gives the same result on every machine. Try "
           "`pba view SCENE --clock variable`, and `pba render SCENE --no-interpolation` to see the stutter that "
           "interpolation hides.\n";
    file.commit();
}

} // namespace pba::app
