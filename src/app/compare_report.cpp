#include "compare_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "atomic_file.hpp"
#include "csv.hpp"
#include "gnuplot.hpp"
#include "study/exact_solution.hpp"
#include "study/findings.hpp"
#include "study/plots.hpp"

namespace pba::app {

using study::ParticleResult;

namespace {

std::string number(double x) { return std::isnan(x) ? "nan" : fmt::format("{}", x); }

} // namespace

std::string integratorTable(const std::vector<Integrator>& integrators, const std::vector<double>& dts, bool markdown,
                            const std::function<std::string(Integrator, double)>& cell)
{
    // Text columns wide enough for the longest name, implicit-gyroscopic.
    std::string out = markdown ? "| integrator" : fmt::format("{:<21}", "integrator \\ dt");
    for (double dt : dts)
        out += markdown ? fmt::format(" | {}", dt) : fmt::format("{:>10}", dt);
    out += markdown ? " |\n|---" : "\n";
    if (markdown) {
        for (std::size_t i = 0; i < dts.size(); ++i)
            out += "|---:";
        out += "|\n";
    }
    for (Integrator integrator : integrators) {
        out += markdown ? fmt::format("| {}", integratorName(integrator)) : fmt::format("{:<21}", integratorName(integrator));
        for (double dt : dts) {
            const std::string value = cell(integrator, dt);
            out += markdown ? " | " + value : fmt::format("{:>10}", value);
        }
        out += markdown ? " |\n" : "\n";
    }
    return out;
}

std::string energyTable(const study::StudyConfig& config, const study::StudyResult& result, CollisionResponse collision,
                        bool markdown)
{
    return integratorTable(config.integrators, config.dts, markdown, [&](Integrator integrator, double dt) {
        const ParticleResult* r = study::findRun(result, integrator, collision, dt);
        return !r ? std::string("-") : std::isnan(r->blewUpAt) ? study::ratioText(r->energyRatioEnd) : std::string("blew up");
    });
}

std::string energyTableHeading(const study::StudyConfig& config, const study::StudyResult& result,
                               CollisionResponse collision)
{
    const std::string what = std::string(result.followsSystem ? "Total energy (every body) at the end over at the start"
                                                              : "Energy at the end over energy at the start") +
                             (result.lessSourceWork ? " (less the dryer's work)" : "");
    if (!study::anyCollision(result) && config.collisions.size() > 1)
        return fmt::format("## {} (nothing collides: every collision response alike)", what);
    const bool withExact = collision == CollisionResponse::Reflect && study::exactShownAsReflect(config, result);
    return fmt::format("## {}, `{}` response{}", what, collisionResponseName(collision),
                       withExact ? " (and `exact`, the same runs here)" : "");
}

std::string centreErrorTable(const study::StudyConfig& config, const study::StudyResult& result,
                             CollisionResponse collision, bool markdown)
{
    return integratorTable(config.integrators, config.dts, markdown, [&](Integrator integrator, double dt) {
        const ParticleResult* r = study::findRun(result, integrator, collision, dt);
        if (!r)
            return std::string("-");
        if (!std::isnan(r->blewUpAt))
            return std::string("blew up");
        return std::isnan(r->errorBeforeImpact) ? std::string("no reference") : fmt::format("{:.3g}", r->errorBeforeImpact);
    });
}

void writeResultsCsv(const std::filesystem::path& path, const study::StudyResult& result)
{
    AtomicFile file(path);
    auto& out = file.stream();
    out << "integrator,collision,dt,particle,steps,energy_ratio_end,mean_energy_ratio,max_energy_deviation,bounces,"
           "apex_ratio_last,period_error,max_position_error,blew_up_at\n";
    for (const auto& r : result.runs)
        out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", integratorName(r.integrator),
                           collisionResponseName(r.collision), r.dt, csvField(r.particle), r.steps, number(r.energyRatioEnd),
                           number(r.meanEnergyRatio), number(r.maxEnergyDeviation), r.bounces, number(r.apexRatioLast), number(r.periodError),
                           number(r.maxPositionError), number(r.blewUpAt));
    file.commit();
}

void writeOrdersCsv(const std::filesystem::path& path, const study::StudyResult& result)
{
    AtomicFile file(path);
    file.stream() << "integrator,dt,max_position_error,measured_order,expected_order\n";
    for (const auto& o : result.orders)
        for (std::size_t i = 0; i < o.dts.size(); ++i)
            file.stream() << fmt::format("{},{},{},{},{}\n", integratorName(o.integrator), o.dts[i], number(o.errors[i]),
                                         number(o.measured), o.expected);
    file.commit();
}

void writeStabilityCsv(const std::filesystem::path& path, const study::StudyResult& result)
{
    AtomicFile file(path);
    file.stream() << "integrator,omega_max,measured_dt_limit,theory_dt_limit\n";
    for (const auto& s : result.stability)
        file.stream() << fmt::format("{},{},{},{}\n", integratorName(s.integrator), s.omegaMax, number(s.measuredDt),
                                     std::isnan(s.theoryDt)   ? std::string("none")
                                     : std::isinf(s.theoryDt) ? std::string("any")
                                                              : number(s.theoryDt));
    file.commit();
}

namespace {

double maxRatio(const study::Series& series)
{
    double most = 0.0;
    for (double e : series.energyRatio)
        most = std::max(most, e);
    return most;
}

std::string stabilityRow(const study::StudyResult& result, const study::StabilityResult& s, bool damped)
{
    const double omega = *result.omegaMax;
    const std::string measured = std::isnan(s.measuredDt) ? "not measured: " + s.unmeasured
                                                          : fmt::format("{:.5g}", s.measuredDt);
    const std::string omegaDt = std::isnan(s.measuredDt) ? std::string("-") : fmt::format("{:.4g}", omega * s.measuredDt);
    if (std::isnan(s.theoryDt))
        return fmt::format("| {} | {} | {} | {} | - |\n", integratorName(s.integrator),
                           damped ? "none undamped (the damping gives it one)" : "none: gains energy at every dt",
                           measured, omegaDt);
    if (std::isinf(s.theoryDt)) {
        const double largest = std::size(study::kLadderOmegaDt) > 0 ? study::kLadderOmegaDt[std::size(study::kLadderOmegaDt) - 1] : 0.0;
        const std::string upTo = std::isnan(s.measuredDt) ? "not measured: " + s.unmeasured
                                 : s.measuredDt * omega >= largest * (1 - 1e-9)
                                     ? fmt::format("stable up to the largest dt tried, {:.5g}", s.measuredDt)
                                     : fmt::format("stable up to {:.5g}, not above (see below)", s.measuredDt);
        return fmt::format("| {} | any: stable at every dt | {} | {} | - |\n", integratorName(s.integrator), upTo, omegaDt);
    }
    const std::string ratio = std::isnan(s.measuredDt) ? std::string("-") : fmt::format("{:.4f}", s.measuredDt / s.theoryDt);
    return fmt::format("| {} | {:.5g} (omega dt = {:.4g}) | {} | {} | {} |\n", integratorName(s.integrator), s.theoryDt,
                       omega * s.theoryDt, measured, omegaDt, ratio);
}

/// Why a measured limit falls short of the theory, from the runs either side of it: the swing
/// leaving the linear regime, or a stability that is not monotone in dt. The theory is for small
/// swings of linear springs; a scene that starts far from that (`spring` starts stretched by
/// half its rest length) is measured by its nonlinearity.
std::string shortOfTheory(const study::StudyConfig& config, const study::StudyResult& result)
{
    const double stretch = study::largestStartStretch(config.scene.world);
    std::string out;
    for (const auto& s : result.stability) {
        const std::string name(integratorName(s.integrator));
        if (!std::isnan(s.measuredDt) && !s.below.stable && !s.below.series.t.empty())
            out += fmt::format("\n{}'s run {:g}% below its measured limit is not stable: stability is not monotone in "
                               "dt here, and the limit is the edge of one stable band, not of every dt below it.\n",
                               name, 100 * study::kStabilityMargin);
        if (std::isnan(s.measuredDt) || std::isnan(s.theoryDt) || s.measuredDt > 0.98 * s.theoryDt)
            continue;
        const double ratio = s.measuredDt / s.theoryDt;
        if (s.above.leftLinearRegime) {
            out += fmt::format("\n{}'s limit is {:.3f} of its theory because a spring leaves lengths (0, 2 L) there, "
                               "not because the energy grows: {}a swing that grows near the limit reaches zero length.",
                               name, ratio,
                               stretch >= 0.01 ? fmt::format("the springs start {:.0f}% off their rest length, and ",
                                                             100 * stretch)
                                               : "");
            // Its modified energy's ellipse, x^2 w^2 (1 - (w dt / 2)^2) ... reaches x = A / sqrt(1 - (w dt/2)^2)
            // from rest at x = A: zero length (x = L) at w dt = 2 sqrt(1 - (A/L)^2). Said only where it is
            // what was measured: a lone spring released from rest, not a cloth sagging under gravity.
            const double predicted = 2.0 * std::sqrt(1.0 - stretch * stretch), measured = s.measuredDt * s.omegaMax;
            if (s.integrator == Integrator::SemiImplicitEuler && stretch >= 0.01 && stretch < 1.0 &&
                std::abs(measured - predicted) <= 0.02 * predicted)
                out += fmt::format(" Semi-implicit Euler keeps a modified energy whose ellipse reaches A / sqrt(1 - "
                                   "(omega dt / 2)^2) from rest at A; with A = {:.2g} L that is L, the spring through "
                                   "zero length, at omega dt = 2 sqrt(1 - (A/L)^2) = {:.4g}, which is what is "
                                   "measured ({:.4g}).",
                                   stretch, predicted, measured);
            out += "\n";
        }
        if (s.above.stable) {
            out += fmt::format("\n{}'s run {:g}% above its measured limit is stable again: stability is not monotone "
                               "in dt here, and the bisection found the edge of one stable band.",
                               name, 100 * study::kStabilityMargin);
            if (s.integrator == Integrator::RK4)
                out += fmt::format(" RK4 evaluates the force at trial states up to dt |v| ahead, omega dt times the "
                                   "swing: with the springs {:.0f}% off their rest length those pass through zero "
                                   "length, where a spring's force turns round, and the step gains energy (the run "
                                   "above peaks at {:.3g} E0) by an amount that depends on where the steps fall in "
                                   "the swing.",
                                   100 * stretch, maxRatio(s.above.series));
            out += "\n";
        }
    }
    if (!out.empty())
        out += "\nThe theory is for small swings: on `stiff-spring`, which starts 2% off its rest length, every limit "
               "measures within 0.3% of it (docs/compare.md).\n";
    return out;
}

/// The energy a run keeps over one period T of the highest mode: E(t)/E0 at the first sample at
/// or after T, scaled to T as (E(t)/E0)^(T/t). Measured over the first period, not the whole run,
/// whose end energy of a strongly damped run is rounding.
double keptPerPeriod(const study::StabilityRun& run, double omega)
{
    const double period = 2.0 * std::numbers::pi / omega;
    const auto& t = run.series.t;
    for (std::size_t i = 1; i < t.size(); ++i)
        if (t[i] >= period * (1 - 1e-9))
            return std::pow(std::max(0.0, run.series.energyRatio[i]), period / t[i]);
    return std::numeric_limits<double>::quiet_NaN();
}

/// The ladder of the methods stable at every dt: what each omega dt costs in damping.
std::string dampingTable(const study::StudyConfig& config, const study::StudyResult& result)
{
    const double periods = config.stability.periods;
    std::string rows;
    for (const auto& s : result.stability) {
        if (s.ladder.empty())
            continue;
        rows += fmt::format("| {}", integratorName(s.integrator));
        for (const auto& run : s.ladder)
            rows += " | " + (run.stable ? fmt::format("{:.3g}", keptPerPeriod(run, s.omegaMax))
                             : run.leftLinearRegime ? std::string("a spring leaves (0, 2 L)")
                                                    : std::string("crosses the bound"));
        rows += " |\n";
    }
    if (rows.empty())
        return "";
    std::string head = fmt::format(
        "\nThe methods stable at every dt pay in damping. Each is run at a ladder of omega dt, up to 128 times "
        "semi-implicit Euler's limit of 2, over the same {:g} periods of the highest mode, stable when its energy "
        "stays under {:g} E0; the table gives the energy kept over the first period T = 2 pi / omega, "
        "E(t)/E0 at the first step t >= T, scaled to T as (E(t)/E0)^(T/t) (an undamped spring keeps 1; backward Euler multiplies a "
        "single oscillator's energy by 1 / (1 + (omega dt)^2) every step, (1 + (omega dt)^2)^(-2 pi / (omega dt)) a "
        "period), or why the run stopped. The energy includes gravity's, so a falling rope's reads near 1 whatever "
        "its springs lose.\n\n| integrator",
        periods, config.stability.energyFactor);
    std::string rule = "|---";
    for (double w : study::kLadderOmegaDt) {
        head += fmt::format(" | omega dt = {:g}", w);
        rule += "|---:";
    }
    return head + " |\n" + rule + "|\n" + rows;
}

} // namespace

std::string stabilitySection(const study::StudyConfig& config, const study::StudyResult& result, bool withPlots)
{
    if (result.stability.empty())
        return "";
    const double omega = *result.omegaMax;
    const auto& c = config.stability;
    const double period = 2.0 * std::numbers::pi / omega;
    std::string out = "## Stability limits\n\n";
    out += fmt::format(
        "The scene's highest natural frequency is omega_max = {:.6g} rad/s (period {:.4g} s): the square root of the "
        "largest eigenvalue of M^-1 K, found by power iteration, with K the springs' stiffness matrix at the start "
        "state (blocks +-k u u^T, the geometric term left out; fixed particles drop out). For an undamped oscillator "
        "of that frequency the theory allows dt < 2 / omega for semi-implicit Euler and velocity Verlet, "
        "dt <= 2 sqrt(2) / omega for RK4 (dissipative below it: slightly at small omega dt, strongly near the limit), and no dt for forward Euler, which gains "
        "energy at every step. The theory counts the springs alone; the runs are the whole scene, its other forces "
        "and surfaces included.\n\n",
        omega, period);
    out += fmt::format(
        "A dt counts as **stable** when the energy (kinetic + potential, all bodies) stays finite and never rises above "
        "E0 + {:g} |E0| ({:g} times a positive start) over {:g} periods of the highest mode ({:.4g} s), and no spring "
        "is stretched to twice its rest length or through zero, where the linear theory ends. The largest "
        "stable dt is bracketed by doubling or halving from omega dt = 1 and bisected until the bracket is {:g} of it "
        "wide. The factor is large on purpose: a stable run near its limit swings far from its start (semi-implicit "
        "Euler released at rest reaches E0 / (1 - omega dt / 2)), while above a limit the energy grows geometrically "
        "and crosses any bound within a few periods.\n\n",
        c.energyFactor - 1.0, c.energyFactor, c.periods, c.periods * period, c.tolerance);
    out += "| integrator | theory dt limit (s) | measured dt limit (s) | omega dt measured | measured / theory |\n"
           "|---|---:|---:|---:|---:|\n";
    // The theory's limits are the undamped springs': damping gives forward Euler a limit of its own.
    const bool damped = study::forceKinds(config.scene.world).dampedSprings;
    for (const auto& s : result.stability)
        out += stabilityRow(result, s, damped);
    if (damped)
        out += "\nThe springs here are damped, and the theory's limits are the undamped springs': damping gives "
               "forward Euler a limit of its own (its growth 1 + (omega dt)^2 a step is offset by the damping: "
               "omega dt < 2 zeta for a mode of damping ratio zeta) and moves semi-implicit Euler's to "
               "omega dt < 2 (sqrt(1 + zeta^2) - zeta); the measured limits include it.\n";
    for (const auto& s : result.stability)
        if (std::isnan(s.theoryDt) && !std::isnan(s.measuredDt) && !damped) {
            const double single = std::log(c.energyFactor) / (2.0 * std::numbers::pi * c.periods);
            const double measured = omega * s.measuredDt;
            out += fmt::format(
                "\nForward Euler's number is the criterion's, not a limit of the method: its energy grows by "
                "1 + (omega dt)^2 every step, about exp(2 pi P omega dt) over P periods, so a single oscillator "
                "reaches {:g} E0 over {:g} periods at omega dt = ln({:g}) / (2 pi {:g}) = {:.4g} (measured here: "
                "{:.4g}{}); a longer horizon or a tighter factor gives a smaller dt, without end.\n",
                c.energyFactor, c.periods, c.energyFactor, c.periods, single, measured,
                measured > 1.2 * single ? ", larger: the highest mode holds a small share of this scene's energy, "
                                          "and its growth must outgrow the rest before the total crosses the bound"
                                        : "");
        }
    out += shortOfTheory(config, result) + dampingTable(config, result);
    if (withPlots)
        out += fmt::format("\n![stability](stability.png)\n\nEach panel: E/E0 at dt {:g}% below (darker, solid) and "
                           "{:g}% above (lighter, dashed) the measured limit; a run above it stops where it crosses "
                           "the bound or a spring leaves the linear regime. Where the limit is not measured (the scene "
                           "leaves the linear regime at any dt, or the method is unstable at every dt tried), the "
                           "panel shows the smallest dt tried and "
                           "omega dt = 1.\n",
                           100 * study::kStabilityMargin, 100 * study::kStabilityMargin);
    return out + "\n";
}

bool writePlots(const std::filesystem::path& dir, const study::StudyConfig& config, const study::StudyResult& result)
{
    if (!gnuplotAvailable())
        return false;
    ScratchDir scratch("pba-compare");
    runGnuplot(study::plotScript(scratch.path(), config, result), scratch.path());
    for (const char* name : study::kPlotFiles)
        publish(scratch.path() / name, dir / name);
    if (!result.stability.empty())
        publish(scratch.path() / study::kStabilityPlotFile, dir / study::kStabilityPlotFile);
    return true;
}

std::string writeWorkPrecision(const std::filesystem::path& dir, const std::vector<study::WorkPrecisionPoint>& points,
                               bool plots)
{
    {
        AtomicFile file(dir / "work_precision.csv");
        auto& out = file.stream();
        out << "scene,integrator,dt,error,cpu_s\n";
        for (const study::WorkPrecisionPoint& p : points)
            if (!p.blewUp)
                out << fmt::format("{},{},{},{},{}\n", p.scene, integratorName(p.integrator), p.dt, p.error, p.cpuSeconds);
        file.commit();
    }
    if (plots) {
        ScratchDir scratch("pba-compare");
        runGnuplot(study::workPrecisionPlotScript(scratch.path(), points), scratch.path());
        publish(scratch.path() / study::kWorkPrecisionPlotFile, dir / study::kWorkPrecisionPlotFile);
    }
    std::string blown;
    for (const study::WorkPrecisionPoint& p : points)
        if (p.blewUp)
            blown += fmt::format("{}{} {} at {:g}", blown.empty() ? "" : ", ", p.scene, integratorName(p.integrator), p.dt);
    return fmt::format(
        "## Work against precision\n\nWhich method reaches an accuracy for the least CPU time: the spring, the chain, "
        "the cloth and the tennis racket, each run for {:g} s (the chain {:g} s: its free end strikes the room's wall "
        "at 0.85 s, and from each impact on the runs part by tenths of a metre whatever the dt, so an error measured "
        "after it is the impacts', not the method's) with every method it takes at dt {}, on one thread, "
        "their error at the end against RK4 at dt = {:g} s (for the racket, the angle between its orientations; for "
        "the others, the largest distance of a particle). A method of order p draws a line of slope -p against its "
        "work; the cheapest method for an accuracy is the lowest line at it. `work_precision.csv` holds every "
        "point, and `pba compare` prints which method reached 1e-3 cheapest on each scene (CPU times change from "
        "run to run, and this report does not).\n\n{}{}",
        study::kWorkPrecisionSeconds, study::kChainSeconds, "0.0005 to 0.02 s", study::kReferenceDt,
        plots ? "![work and precision](work_precision.png)\n\n" : "",
        blown.empty() ? std::string() : fmt::format("Left out, they blew up: {}.\n\n", blown));
}

namespace {

std::string whatIsMeasured(const study::StudyResult& result)
{
    if (!result.followsSystem)
        return "Each moving particle is compared with its exact solution where the scene has one (a bounce, an "
               "oscillator). ";
    return fmt::format(
        "Several bodies move and none has an exact solution, so the study follows the whole system, not one of its "
        "particles: its total energy (kinetic + potential, every body) and its centre of mass. With no exact "
        "solution to compare with, the reference is a run of the same method and response at dt = {:g} s (a quarter "
        "of the smallest dt studied); its own error is part of each figure, and a method that blows up at that dt "
        "has no reference. ",
        result.referenceDt);
}

/// The heading of a centre-of-mass table and what its window is: up to the reference's first
/// impact, and how far the runs part over the whole run.
std::string centreErrorHeading(const study::StudyConfig& config, const study::StudyResult& result,
                               CollisionResponse collision)
{
    const bool withExact = collision == CollisionResponse::Reflect && study::exactShownAsReflect(config, result);
    double firstImpact = std::numeric_limits<double>::infinity(), least = firstImpact, most = 0.0;
    bool anyImpact = false; // at any dt
    // Whether the impacts, not the method, make the whole run's error: at the smallest dt it is
    // over ten times the error before the first impact for every method with a reference.
    bool impactsDominate = true, anyFinest = false;
    for (const ParticleResult& r : result.runs)
        if (r.particle == study::kSystemRow && r.collision == collision) {
            anyImpact = anyImpact || !std::isnan(r.firstImpactAt);
            if (!std::isnan(r.firstImpactAt) && r.dt == config.dts.front())
                firstImpact = std::min(firstImpact, r.firstImpactAt);
            if (std::isnan(r.blewUpAt) && !std::isnan(r.maxPositionError)) {
                least = std::min(least, r.maxPositionError);
                most = std::max(most, r.maxPositionError);
                if (r.dt == config.dts.front()) {
                    anyFinest = true;
                    impactsDominate = impactsDominate && r.maxPositionError > 10.0 * r.errorBeforeImpact;
                }
            }
        }
    std::string text = fmt::format("## Centre of mass: largest distance from the reference run (m), `{}` response{}\n\n",
                                   collisionResponseName(collision), withExact ? " (and `exact`)" : "");
    if (std::isinf(firstImpact))
        return text + (anyImpact ? "At the smallest dt nothing met a surface over the whole run; at larger dt some "
                                   "runs did, and their bounces part them from the reference."
                                 : "Over the whole run: nothing met a surface.");
    text += fmt::format("Up to the reference's first impact (t = {:.3g} s at the smallest dt), where the motion is "
                        "smooth: there the distance should fall with dt at the method's order{}.",
                        firstImpact,
                        result.lessSourceWork ? " where the forces are smooth too (the edge of the dryer's cone is "
                                                "not, and a body crossing it breaks the order)"
                                              : "");
    if (most > 0.0)
        text += fmt::format(" Over the whole run (`max_position_error` in `results.csv`) the runs part by {:.3g} to "
                            "{:.3g} m.",
                            least, most);
    if (most > 0.0 && anyFinest && impactsDominate)
        text += " At the smallest dt that is over ten times the distance before the impact, for every method: each "
                "impact is met a step late and put right by the response, which moves the particle by a fraction of "
                "a step that differs from dt to dt, and the bounces that follow amplify the difference.";
    return text;
}

} // namespace

void writeReport(const std::filesystem::path& path, const study::StudyConfig& config, const study::StudyResult& result,
                 bool withPlots, const std::string& workPrecision)
{
    AtomicFile file(path);
    auto& out = file.stream();
    out << fmt::format("# Integrator study: {}\n\n", config.scene.name);
    out << fmt::format("Scene `{}`, {} s of simulated time, {}. {}The columns of `results.csv` are described in "
                       "docs/compare.md.\n\n",
                       config.scene.name, config.duration, study::describeDts(config.dts), whatIsMeasured(result));
    out << "## Findings\n\n" << study::findings(config, result) << "\n";
    for (CollisionResponse c : study::distinctResponses(config, result))
        out << energyTableHeading(config, result, c) << "\n\n" << energyTable(config, result, c, true) << "\n";
    if (result.followsSystem)
        for (CollisionResponse c : study::distinctResponses(config, result))
            out << centreErrorHeading(config, result, c) << "\n\n" << centreErrorTable(config, result, c, true) << "\n";
    out << "## Orders of accuracy (spring scene, max position error over 2 s)\n\n| integrator | measured | expected |\n"
           "|---|---:|---:|\n";
    for (const auto& o : result.orders)
        out << fmt::format("| {} | {} | {} |\n", integratorName(o.integrator), study::orderText(o), o.expected);
    out << "\n" << stabilitySection(config, result, withPlots) << workPrecision;
    if (withPlots)
        out << "## Plots\n\n![height](height.png)\n\n![energy](energy.png)\n\n![convergence](convergence.png)\n";
    else
        out << "(No plots: gnuplot is not installed; install the Debian package gnuplot-nox.)\n";
    file.commit();
}

} // namespace pba::app
