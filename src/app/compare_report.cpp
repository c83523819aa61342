#include "compare_report.hpp"

#include <cmath>

#include <fmt/format.h>

#include "atomic_file.hpp"
#include "csv.hpp"
#include "gnuplot.hpp"
#include "study/findings.hpp"
#include "study/plots.hpp"

namespace pba::app {

using study::ParticleResult;

namespace {

std::string number(double x) { return std::isnan(x) ? "nan" : fmt::format("{}", x); }

} // namespace

std::string energyTable(const study::StudyConfig& config, const study::StudyResult& result, CollisionResponse collision,
                        bool markdown)
{
    std::string out;
    out += markdown ? "| integrator" : fmt::format("{:<20}", "integrator \\ dt");
    for (double dt : config.dts)
        out += markdown ? fmt::format(" | {}", dt) : fmt::format("{:>10}", dt);
    out += markdown ? " |\n|---" : "\n";
    if (markdown) {
        for (std::size_t i = 0; i < config.dts.size(); ++i)
            out += "|---:";
        out += "|\n";
    }
    for (Integrator integrator : config.integrators) {
        out += markdown ? fmt::format("| {}", integratorName(integrator)) : fmt::format("{:<20}", integratorName(integrator));
        for (double dt : config.dts) {
            const ParticleResult* r = study::findRun(result, integrator, collision, dt);
            const std::string value = r ? fmt::format("{:.4f}", r->energyRatioEnd) : "-";
            out += markdown ? " | " + value : fmt::format("{:>10}", value);
        }
        out += markdown ? " |\n" : "\n";
    }
    return out;
}

std::string energyTableHeading(const study::StudyConfig& config, const study::StudyResult& result,
                               CollisionResponse collision)
{
    if (study::distinctResponses(config, result).size() < config.collisions.size())
        return "## Energy at the end over energy at the start (nothing collides: every collision response alike)";
    return fmt::format("## Energy at the end over energy at the start, `{}` response", collisionResponseName(collision));
}

void writeResultsCsv(const std::filesystem::path& path, const study::StudyResult& result)
{
    AtomicFile file(path);
    auto& out = file.stream();
    out << "integrator,collision,dt,particle,steps,energy_ratio_end,mean_energy_ratio,max_energy_deviation,bounces,"
           "apex_ratio_last,period_error,max_position_error\n";
    for (const auto& r : result.runs)
        out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", integratorName(r.integrator),
                           collisionResponseName(r.collision), r.dt, csvField(r.particle), r.steps, number(r.energyRatioEnd),
                           number(r.meanEnergyRatio), number(r.maxEnergyDeviation), r.bounces, number(r.apexRatioLast), number(r.periodError),
                           number(r.maxPositionError));
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

bool writePlots(const std::filesystem::path& dir, const study::StudyConfig& config, const study::StudyResult& result)
{
    if (!gnuplotAvailable())
        return false;
    ScratchDir scratch("pba-compare");
    runGnuplot(study::plotScript(scratch.path(), config, result), scratch.path());
    for (const char* name : study::kPlotFiles)
        publish(scratch.path() / name, dir / name);
    return true;
}

void writeReport(const std::filesystem::path& path, const study::StudyConfig& config, const study::StudyResult& result,
                 bool withPlots)
{
    AtomicFile file(path);
    auto& out = file.stream();
    out << fmt::format("# Integrator study: {}\n\n", config.scene.name);
    out << fmt::format("Scene `{}`, {} s of simulated time, {}. Each moving particle is compared with its exact "
                       "solution; the columns of `results.csv` are described in docs/compare.md.\n\n",
                       config.scene.name, config.duration, study::describeDts(config.dts));
    out << "## Findings\n\n" << study::findings(config, result) << "\n";
    for (CollisionResponse c : study::distinctResponses(config, result))
        out << energyTableHeading(config, result, c) << "\n\n" << energyTable(config, result, c, true) << "\n";
    out << "## Orders of accuracy (spring scene, max position error over 2 s)\n\n| integrator | measured | expected |\n"
           "|---|---:|---:|\n";
    for (const auto& o : result.orders)
        out << fmt::format("| {} | {} | {} |\n", integratorName(o.integrator), study::orderText(o), o.expected);
    if (withPlots)
        out << "\n## Plots\n\n![height](height.png)\n\n![energy](energy.png)\n\n![convergence](convergence.png)\n";
    else
        out << "\n(No plots: gnuplot is not installed; install the Debian package gnuplot-nox.)\n";
    file.commit();
}

} // namespace pba::app
