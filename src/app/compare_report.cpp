#include "compare_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#include <fmt/format.h>

#include "atomic_file.hpp"
#include "csv.hpp"
#include "gnuplot.hpp"
#include "study/exact_solution.hpp"

namespace pba::app {

namespace {

using study::ParticleResult;

/// The first moving particle's result for one configuration, or null.
const ParticleResult* find(const study::StudyResult& result, Integrator integrator, CollisionResponse collision, double dt)
{
    for (const auto& r : result.runs)
        if (r.integrator == integrator && r.collision == collision && r.dt == dt)
            return &r;
    return nullptr;
}

std::string number(double x) { return std::isnan(x) ? "nan" : fmt::format("{}", x); }

double closest(const std::vector<double>& values, double target)
{
    return *std::min_element(values.begin(), values.end(),
                             [&](double a, double b) { return std::abs(std::log(a / target)) < std::abs(std::log(b / target)); });
}

bool has(const std::vector<Integrator>& list, Integrator x) { return std::find(list.begin(), list.end(), x) != list.end(); }
bool has(const std::vector<CollisionResponse>& list, CollisionResponse x)
{
    return std::find(list.begin(), list.end(), x) != list.end();
}

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
            const ParticleResult* r = find(result, integrator, collision, dt);
            const std::string value = r ? fmt::format("{:.4f}", r->energyRatioEnd) : "-";
            out += markdown ? " | " + value : fmt::format("{:>10}", value);
        }
        out += markdown ? " |\n" : "\n";
    }
    return out;
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

namespace {

void writeSeries(const std::filesystem::path& path, const study::Series& s, bool energy)
{
    std::ofstream out(path);
    for (std::size_t i = 0; i < s.t.size(); ++i)
        out << s.t[i] << ' ' << (energy ? s.energyRatio[i] : s.y[i]) << '\n';
}

std::string heightPlot(const std::filesystem::path& dir, const study::StudyConfig& config, const study::StudyResult& result)
{
    const CollisionResponse collision = config.collisions.front();
    std::vector<double> shown{config.dts.front()};
    for (double target : {0.01, 0.05})
        if (double dt = closest(config.dts, target); std::find(shown.begin(), shown.end(), dt) == shown.end())
            shown.push_back(dt);
    // The exact trajectory of the first moving particle, if the scene has one.
    std::size_t first = 0;
    while (first < config.scene.world.bodyCount() && config.scene.world.body(first).isFixed())
        ++first;
    const auto exact = first < config.scene.world.bodyCount() ? study::ExactSolution::find(config.scene.world, first)
                                                              : std::nullopt;
    std::string plots;
    if (exact) {
        std::ofstream out(dir / "exact.dat");
        for (int i = 0; i <= 4000; ++i) {
            const double t = config.duration * i / 4000.0;
            out << t << ' ' << exact->position(t).y << '\n';
        }
    }
    const double start = first < config.scene.world.bodyCount() ? config.scene.world.body(first).getPos().y : 0.0;
    std::string script = fmt::format("set terminal pngcairo size 1400,900 font 'sans,10'\nset output 'height.png'\n"
                                     "set multiplot layout 2,2 title 'height against time ({} collision response)'\n"
                                     "set xlabel 't (s)'\nset ylabel 'y (m)'\nset key outside right\n",
                                     collisionResponseName(collision));
    for (Integrator integrator : config.integrators) {
        std::string line = fmt::format("set title '{}'\nplot ", integratorName(integrator));
        for (double dt : shown) {
            const ParticleResult* r = find(result, integrator, collision, dt);
            if (!r)
                continue;
            const std::string file = fmt::format("h_{}_{}.dat", integratorName(integrator), dt);
            writeSeries(dir / file, r->series, false);
            line += fmt::format("'{}' with lines lw 1.5 title 'dt = {}', ", file, dt);
        }
        if (exact)
            line += "'exact.dat' with lines lw 1 dt 2 lc rgb 'black' title 'exact', ";
        line += fmt::format("{} with lines lc rgb 'gray50' dt 3 title 'start height'\n", start);
        script += line;
    }
    return script + "unset multiplot\n";
}

std::string energyPlot(const std::filesystem::path& dir, const study::StudyConfig& config, const study::StudyResult& result)
{
    const double dt = closest(config.dts, 0.01);
    std::string script = fmt::format("set terminal pngcairo size 1400,500 font 'sans,10'\nset output 'energy.png'\n"
                                     "set multiplot layout 1,{} title 'energy over its start value, dt = {} s'\n"
                                     "set xlabel 't (s)'\nset ylabel 'E / E0'\nset key top left\n",
                                     config.collisions.size(), dt);
    for (CollisionResponse collision : config.collisions) {
        std::string line = fmt::format("set title '{} response'\nplot ", collisionResponseName(collision));
        for (Integrator integrator : config.integrators) {
            const ParticleResult* r = find(result, integrator, collision, dt);
            if (!r)
                continue;
            const std::string file = fmt::format("e_{}_{}.dat", integratorName(integrator), collisionResponseName(collision));
            writeSeries(dir / file, r->series, true);
            line += fmt::format("'{}' with lines lw 1.5 title '{}', ", file, integratorName(integrator));
        }
        script += line + "1 with lines lc rgb 'gray50' dt 3 title 'exact'\n";
    }
    return script + "unset multiplot\n";
}

std::string convergencePlot(const std::filesystem::path& dir, const study::StudyResult& result)
{
    std::string plot;
    for (const auto& o : result.orders) {
        const std::string file = fmt::format("order_{}.dat", integratorName(o.integrator));
        std::ofstream out(dir / file);
        for (std::size_t i = 0; i < o.dts.size(); ++i)
            if (o.errors[i] > 0)
                out << o.dts[i] << ' ' << o.errors[i] << '\n';
        plot += fmt::format("'{}' with linespoints lw 2 title '{} (measured order {:.2f})', ", file,
                            integratorName(o.integrator), o.measured);
    }
    return "set terminal pngcairo size 900,700 font 'sans,11'\nset output 'convergence.png'\n"
           "set title \"position error against dt on the spring (harmonic oscillator)\"\n"
           "set logscale xy\nset format y '10^{%L}'\nset xlabel 'dt (s)'\nset ylabel 'max position error over 2 s (m)'\n"
           "set key bottom right\nplot " +
           plot +
           "0.5*x with lines dt 2 lc rgb 'gray40' title 'slope 1', 0.5*x**2 with lines dt 3 lc rgb 'gray40' title "
           "'slope 2', 0.02*x**4 with lines dt 4 lc rgb 'gray40' title 'slope 4'\n";
}

} // namespace

bool writePlots(const std::filesystem::path& dir, const study::StudyConfig& config, const study::StudyResult& result)
{
    if (!gnuplotAvailable())
        return false;
    ScratchDir scratch("pba-compare");
    const std::string script = heightPlot(scratch.path(), config, result) + energyPlot(scratch.path(), config, result) +
                               convergencePlot(scratch.path(), result);
    runGnuplot(script, scratch.path());
    for (const char* name : {"height.png", "energy.png", "convergence.png"})
        publish(scratch.path() / name, dir / name);
    return true;
}

std::string findings(const study::StudyConfig& config, const study::StudyResult& result)
{
    std::string text;
    auto ratios = [&](Integrator integrator, CollisionResponse collision, double maxDt, bool mean) {
        std::vector<double> values;
        for (double dt : config.dts)
            if (dt <= maxDt + 1e-12)
                if (const ParticleResult* r = find(result, integrator, collision, dt))
                    values.push_back(mean ? r->meanEnergyRatio : r->energyRatioEnd);
        return values;
    };
    const double lo = config.dts.front(), hi = config.dts.back();
    if (has(config.integrators, Integrator::ForwardEuler)) {
        text += "**Forward Euler gains energy.** ";
        for (CollisionResponse c : config.collisions) {
            const ParticleResult* a = find(result, Integrator::ForwardEuler, c, lo);
            const ParticleResult* b = find(result, Integrator::ForwardEuler, c, hi);
            if (a && b)
                text += fmt::format("With the {} response its energy after {} s is {:.4f} times the start at dt = {} "
                                    "and {:.3f} times at dt = {}. ",
                                    collisionResponseName(c), config.duration, a->energyRatioEnd, lo, b->energyRatioEnd, hi);
        }
        text += "It moves each step with the velocity of the step's start, so every fall ends faster than it "
                "began: the error only ever adds energy, and more of it the larger dt.\n\n";
    }
    if (has(config.integrators, Integrator::SemiImplicitEuler)) {
        const auto reflect = ratios(Integrator::SemiImplicitEuler, CollisionResponse::Reflect, 0.05, true);
        const auto exact = ratios(Integrator::SemiImplicitEuler, CollisionResponse::Exact, 0.05, false);
        text += "**Semi-implicit Euler: the collision response decides the verdict.** ";
        if (has(config.collisions, CollisionResponse::Reflect) && !reflect.empty()) {
            double worst = 0;
            for (double r : reflect)
                worst = std::max(worst, std::abs(r - 1));
            text += fmt::format("With the classic `reflect` response its energy, averaged over the run, stays "
                                "within {:.1f}% of the start for every dt up to 0.05 (at any one instant it swings by "
                                "about g |v| dt / 2 per unit mass around that): the practical's observation that it "
                                "keeps its bounce. ",
                                100 * worst);
        }
        if (has(config.collisions, CollisionResponse::Exact) && !exact.empty())
            text += fmt::format("With the `exact` time-of-impact response it loses energy at every bounce and ends "
                                "at {:.3f} of its start energy at dt = {}{}: between bounces it conserves the shadow "
                                "energy E - m g v dt / 2, and each bounce, by reversing v, lowers that level by "
                                "m g |v| dt; the mirror of `reflect` happens to undo the shift.",
                                exact.back(), std::min(0.05, closest(config.dts, 0.05)),
                                exact.back() < 0.01 ? " (it has come to rest on the ground)" : "");
        text += "\n\n";
    }
    for (Integrator integrator : {Integrator::VelocityVerlet, Integrator::RK4}) {
        if (!has(config.integrators, integrator) || !has(config.collisions, CollisionResponse::Exact))
            continue;
        double period = 0, apex = 0;
        bool any = false;
        for (double dt : config.dts)
            if (const ParticleResult* r = find(result, integrator, CollisionResponse::Exact, dt);
                r && !std::isnan(r->periodError) && !std::isnan(r->apexRatioLast)) {
                period = std::max(period, std::abs(r->periodError));
                apex = std::max(apex, std::abs(r->apexRatioLast - 1));
                any = true;
            }
        if (any)
            text += fmt::format("**{} with exact impacts is exact.** Its bounce period is off by at most {:.1e} and "
                                "its last apex by at most {:.1e} (relative) over every dt from {} to {}: it integrates "
                                "constant gravity exactly and the time of impact adds no error.\n\n",
                                integratorName(integrator), period, apex, lo, hi);
    }
    if (!result.orders.empty()) {
        text += "**Orders of accuracy** measured on the harmonic oscillator: ";
        for (const auto& o : result.orders)
            text += fmt::format("{} {:.2f} (expected {}); ", integratorName(o.integrator), o.measured, o.expected);
        text += "each halving of dt divides the error by 2 to the order.\n";
    }
    return text;
}

void writeReport(const std::filesystem::path& path, const study::StudyConfig& config, const study::StudyResult& result,
                 bool withPlots)
{
    AtomicFile file(path);
    auto& out = file.stream();
    out << fmt::format("# Integrator study: {}\n\n", config.scene.name);
    out << fmt::format("Scene `{}`, {} s of simulated time, dt from {} to {} s. Each moving particle is compared with "
                       "its exact solution; the columns of `results.csv` are described in docs/compare.md.\n\n",
                       config.scene.name, config.duration, config.dts.front(), config.dts.back());
    out << "## Findings\n\n" << findings(config, result) << "\n";
    for (CollisionResponse c : config.collisions)
        out << fmt::format("## Energy at the end over energy at the start, `{}` response\n\n", collisionResponseName(c))
            << energyTable(config, result, c, true) << "\n";
    out << "## Orders of accuracy (spring scene, max position error over 2 s)\n\n| integrator | measured | expected |\n"
           "|---|---:|---:|\n";
    for (const auto& o : result.orders)
        out << fmt::format("| {} | {:.2f} | {} |\n", integratorName(o.integrator), o.measured, o.expected);
    if (withPlots)
        out << "\n## Plots\n\n![height](height.png)\n\n![energy](energy.png)\n\n![convergence](convergence.png)\n";
    else
        out << "\n(No plots: gnuplot is not installed; install the Debian package gnuplot-nox.)\n";
    file.commit();
}

} // namespace pba::app
