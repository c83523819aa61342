#include "rotation_report.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "atomic_file.hpp"
#include "compare_report.hpp"
#include "csv.hpp"
#include "gnuplot.hpp"
#include "study/exact_solution.hpp"
#include "study/findings.hpp"
#include "study/rotation_plots.hpp"

namespace pba::app {

namespace {

std::string number(double x) { return std::isnan(x) ? "nan" : fmt::format("{}", x); }

const study::RotationRun* findRun(const study::RotationResult& result, Integrator integrator, double dt)
{
    for (const auto& r : result.runs)
        if (r.integrator == integrator && r.dt == dt)
            return &r;
    return nullptr;
}

std::string cell(const study::RotationRun* r, RotationMeasure measure, double exactPeriod)
{
    if (!r)
        return "-";
    if (!std::isnan(r->blewUpAt))
        return "blew up";
    switch (measure) {
    case RotationMeasure::EnergyDrift: return fmt::format("{:.2e}", r->maxEnergyDrift);
    case RotationMeasure::MomentumDrift:
        return std::isnan(r->maxMomentumDrift) ? "no spin" : fmt::format("{:.2e}", r->maxMomentumDrift);
    case RotationMeasure::PeriodError:
        return std::isnan(r->flipPeriod) ? "no flips" : fmt::format("{:+.2e}", r->flipPeriod / exactPeriod - 1.0);
    }
    return "?";
}

/// The runs at the largest dt that did not blow up, for the findings: the dt where the methods differ most.
double largestDt(const study::RotationConfig& config) { return config.dts.empty() ? 0.0 : config.dts.back(); }

/// Whether forward and semi-implicit Euler drifted alike at dt (their rotations are one step).
bool sameEulers(const study::RotationResult& result, double dt)
{
    const study::RotationRun* forward = nullptr;
    const study::RotationRun* semi = nullptr;
    for (const study::RotationRun& r : result.runs) {
        if (r.dt == dt && r.integrator == Integrator::ForwardEuler)
            forward = &r;
        if (r.dt == dt && r.integrator == Integrator::SemiImplicitEuler)
            semi = &r;
    }
    return forward && semi && forward->maxEnergyDrift == semi->maxEnergyDrift;
}

/// Why the body is no free body, for the measure, or nothing if it is one: the contacts it met in
/// some run, the joint that holds it. Then its drifts are not its method's alone.
std::string notFreeBecause(const study::RotationConfig& config, const study::RotationResult& result, bool momentum)
{
    const bool touched =
        std::any_of(result.runs.begin(), result.runs.end(), [](const study::RotationRun& r) { return r.touched; });
    const bool forced = !study::forceKinds(config.scene.world).onlyGravity; // a dryer's air, drag
    std::vector<std::string> what, how;
    if (touched) {
        what.emplace_back("it touches other bodies or the room");
        how.emplace_back(momentum ? "the contacts turn L" : "contacts take energy by friction and inelastic impacts");
    }
    if (result.joined) {
        what.emplace_back("a joint holds it");
        how.emplace_back(momentum ? "the joint turns L" : "a joint's corrections move it");
    }
    if (forced) {
        what.emplace_back("forces other than gravity act on it");
        how.emplace_back(momentum ? "they turn L" : "they do work on it (the dryer's air lifts it)");
    }
    if (what.empty())
        return {};
    return fmt::format(" `{}` is no free body here ({}): {}, so the drift is theirs as well as the method's.\n\n",
                       result.body, study::listText(what), study::listText(how));
}

/// A measure's findings in a sentence per method at the largest dt: how far it drifted, or that
/// it blew up, and (for |L|) which methods keep it to rounding.
std::string driftFindings(const study::RotationConfig& config, const study::RotationResult& result, bool momentum)
{
    const double dt = largestDt(config);
    if (momentum && std::all_of(result.runs.begin(), result.runs.end(),
                                [](const study::RotationRun& r) { return std::isnan(r.maxMomentumDrift); }))
        return fmt::format("`{}` starts without spin: it has no |L| to keep, so this measure says nothing of the "
                           "methods here.\n\n", result.body);
    std::string out = fmt::format("At the largest dt, {:g} s:", dt);
    for (const study::RotationRun& r : result.runs) {
        if (r.dt != dt)
            continue;
        const double drift = momentum ? r.maxMomentumDrift : r.maxEnergyDrift;
        out += !std::isnan(r.blewUpAt) ? fmt::format(" {} blew up at t = {:.3g} s;", integratorName(r.integrator), r.blewUpAt)
               : momentum && drift < 1e-12
                   ? fmt::format(" {} keeps |L| to rounding ({:.1e});", integratorName(r.integrator), drift)
                   : fmt::format(" {} drifts by up to {:.3g}{};", integratorName(r.integrator), drift,
                                 momentum ? "" : (r.energyRatioEnd > 1.0 ? " (gaining)" : " (losing)"));
    }
    out.back() = '.';
    if (const std::string notFree = notFreeBecause(config, result, momentum); !notFree.empty())
        return out + notFree;
    out += momentum ? " A free body's torque-free step must keep L; a method that integrates omega rather than "
                      "turning L with the body changes |L|, and the implicit gyroscopic step damps it.\n\n"
                    : " Losing energy is the implicit gyroscopic step's dissipation; a bounded drift that does not "
                      "grow with time is the splitting's.\n\n";
    if (!momentum && sameEulers(result, dt))
        out.insert(out.size() - 2, " Forward and semi-implicit Euler give the same numbers: on a free body they differ "
                                   "only in the translation (which velocity moves the position), and their rotation "
                                   "step is the same explicit one, which gains energy.");
    return out;
}

} // namespace

std::string rotationTable(const study::RotationConfig& config, const study::RotationResult& result,
                          RotationMeasure measure, bool markdown)
{
    return integratorTable(config.integrators, config.dts, markdown, [&](Integrator integrator, double dt) {
        return cell(findRun(result, integrator, dt), measure, result.exactPeriod);
    });
}

void writeRotationCsv(const std::filesystem::path& path, const study::RotationResult& result)
{
    AtomicFile file(path);
    auto& out = file.stream();
    out << "integrator,dt,body,steps,energy_ratio_end,max_energy_drift,max_momentum_drift,flips,flip_period,"
           "exact_period,blew_up_at\n";
    for (const auto& r : result.runs)
        out << fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", integratorName(r.integrator), r.dt, csvField(result.body),
                           r.steps, number(r.energyRatioEnd), number(r.maxEnergyDrift), number(r.maxMomentumDrift),
                           r.flips, number(r.flipPeriod), number(result.exactPeriod), number(r.blewUpAt));
    file.commit();
}

bool writeRotationPlots(const std::filesystem::path& dir, const study::RotationConfig& config,
                        const study::RotationResult& result)
{
    if (!gnuplotAvailable())
        return false;
    ScratchDir scratch("pba-compare");
    runGnuplot(study::rotationPlotScript(scratch.path(), config, result), scratch.path(), {result.body});
    publish(scratch.path() / study::kDriftPlotFile, dir / study::kDriftPlotFile);
    if (result.intermediateAxis >= 0)
        publish(scratch.path() / study::kFlipPlotFile, dir / study::kFlipPlotFile);
    if (!std::isnan(result.exactPeriod))
        publish(scratch.path() / study::kPeriodPlotFile, dir / study::kPeriodPlotFile);
    return true;
}

void writeRotationReport(const std::filesystem::path& path, const study::RotationConfig& config,
                         const study::RotationResult& result, bool withPlots)
{
    AtomicFile file(path);
    auto& out = file.stream();
    out << fmt::format("# Rotation study: {}\n\n", config.scene.name);
    out << fmt::format("Scene `{}`, {} s of simulated time, every integrator at every dt, following the rigid body "
                       "`{}`. Its energy includes the rotational term 1/2 omega . L; |L| is its angular momentum "
                       "about its centre of mass, conserved only while no torque acts (no contact, no force at a "
                       "point). The columns of `results.csv` are described in docs/compare.md.\n\n",
                       config.scene.name, config.duration, result.body);
    out << "## Largest energy drift, max |E/E0 - 1|\n\n" << driftFindings(config, result, false)
        << rotationTable(config, result, RotationMeasure::EnergyDrift, true);
    out << "\n## Largest drift of |L|, max ||L|/|L0| - 1|\n\n" << driftFindings(config, result, true)
        << rotationTable(config, result, RotationMeasure::MomentumDrift, true);
    if (!std::isnan(result.exactPeriod) && result.flips)
        out << fmt::format("\n## Flip period against the exact one\n\nSpun near its intermediate axis, a free body "
                           "flips over and back with the period T = 4 K(k) sqrt(a b c / ((b - a)(2 E c - L^2))) (K the "
                           "complete elliptic integral of the first kind): here T_exact = {:.6f} s. Each cell is "
                           "(T - T_exact) / T_exact. An error near -1/2 or below is no longer a period error: a "
                           "method that drifts the energy across the separatrix stops the flip, and what it "
                           "measures is a wobble about another axis (see flip.png).\n\n",
                           result.exactPeriod)
            << rotationTable(config, result, RotationMeasure::PeriodError, true);
    else if (!std::isnan(result.exactPeriod))
        out << fmt::format("\n## Wobble period against the exact one\n\nSpun nearer its largest or smallest axis than "
                           "its intermediate one, this body does not flip: it wobbles, its spin about the intermediate "
                           "axis changing sign with the period T = 4 K(k) sqrt(a b c / ((b - a)(2 E c - L^2))) (K the "
                           "complete elliptic integral of the first kind, a and c swapped for the largest axis): "
                           "here T_exact = {:.6f} s. Each cell is (T - T_exact) / T_exact.\n\n",
                           result.exactPeriod)
            << rotationTable(config, result, RotationMeasure::PeriodError, true);
    else
        out << fmt::format("\nNo flip period: {}.\n",
                           result.intermediateAxis < 0 ? "the body has two equal moments of inertia"
                           : !result.spins             ? "the body starts without spin"
                                                       : "the body spins exactly about a principal axis");
    out << "\n";
    if (withPlots) {
        out << "## Plots\n\n![drift](drift.png)\n";
        if (result.intermediateAxis >= 0)
            out << "\n![flip](flip.png)\n";
        if (!std::isnan(result.exactPeriod))
            out << "\n![period](period.png)\n";
    } else {
        out << "(No plots: gnuplot is not installed; install the Debian package gnuplot-nox.)\n";
    }
    file.commit();
}

} // namespace pba::app
