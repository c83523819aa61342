#include "plots.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "exact_solution.hpp"
#include "findings.hpp"
#include "render/palette.hpp"

namespace pba::study {

namespace {

double closest(const std::vector<double>& values, double target)
{
    return *std::min_element(values.begin(), values.end(),
                             [&](double a, double b) { return std::abs(std::log(a / target)) < std::abs(std::log(b / target)); });
}

void writeSeries(const std::filesystem::path& path, const Series& s, bool energy)
{
    std::ofstream out(path);
    for (std::size_t i = 0; i < s.t.size(); ++i)
        out << s.t[i] << ' ' << (energy ? s.energyRatio[i] : s.y[i]) << '\n';
}

std::string colour(Integrator integrator, double shade = 0.0)
{
    return palette::hex(palette::shade(palette::integratorRgb(integrator), shade));
}

/// One panel per integrator, laid out so that none is left empty.
std::string multiplot(std::size_t panels, const std::string& output, const std::string& title, int rowHeight = 450)
{
    const std::size_t columns = panels == 1 ? 1 : 2, rows = panels <= 2 ? 1 : 2;
    return fmt::format("set terminal pngcairo size {},{} font 'sans,10'\nset output '{}'\n"
                       "set multiplot layout {},{} title '{}'\n",
                       columns == 1 ? 900 : 1400, rows == 1 ? rowHeight + 30 : 2 * rowHeight, output, rows, columns,
                       title);
}

/// The first moving particle, the one the plots follow.
std::size_t firstMoving(const World& world)
{
    std::size_t first = 0;
    while (first < world.bodyCount() && world.body(first).isFixed())
        ++first;
    return first;
}

/// How far line k of n is moved from its integrator's colour: 0 for the typical one, towards
/// black before it, towards white after it.
double shadeOf(std::size_t k, std::size_t typical, std::size_t n)
{
    if (k < typical)
        return -0.45 * double(typical - k) / double(typical);
    if (k > typical)
        return 0.45 * double(k - typical) / double(n - 1 - typical);
    return 0.0;
}

std::string heightPlot(const std::filesystem::path& dir, const StudyConfig& config, const StudyResult& result)
{
    const CollisionResponse collision = distinctResponses(config, result).front();
    // The smallest dt, a typical one and a large one: each integrator's line in shades of its
    // colour, its own for the typical dt, darker for smaller dt and lighter for larger.
    std::vector<double> shown{config.dts.front()};
    for (double target : {0.01, 0.05})
        if (double dt = closest(config.dts, target); std::find(shown.begin(), shown.end(), dt) == shown.end())
            shown.push_back(dt);
    std::sort(shown.begin(), shown.end());
    const auto typical = std::size_t(std::find(shown.begin(), shown.end(), closest(config.dts, 0.01)) - shown.begin());
    const World& world = config.scene.world;
    const std::size_t first = firstMoving(world);
    const auto exact = first < world.bodyCount() ? ExactSolution::find(world, first) : std::nullopt;
    if (exact) {
        std::ofstream out(dir / "exact.dat");
        for (int i = 0; i <= 4000; ++i) {
            const double t = config.duration * i / 4000.0;
            out << t << ' ' << exact->position(t).y << '\n';
        }
    }
    const ParticleResult* any = findRun(result, config.integrators.front(), collision, config.dts.front());
    const double start = any && !any->series.y.empty()       ? any->series.y.front()
                         : first < world.bodyCount() ? world.body(first).getPos().y
                                                     : 0.0;
    // Without collisions every response gives the same motion: naming one would mislead.
    const std::string what = result.followsSystem ? "height of the centre of mass" : "height";
    const std::string title = anyCollision(result) ? fmt::format("{} against time ({} collision response)", what,
                                                                 collisionResponseName(collision))
                                                   : what + " against time";
    std::string script = multiplot(config.integrators.size(), "height.png", title) +
                         fmt::format("set xlabel 't (s)'\nset ylabel '{} (m)'\nset key outside right\n",
                                     result.followsSystem ? "centre of mass y" : "y");
    for (Integrator integrator : config.integrators) {
        std::string line = fmt::format("set title '{}'\nplot ", integratorName(integrator));
        for (std::size_t k = 0; k < shown.size(); ++k) {
            const ParticleResult* r = findRun(result, integrator, collision, shown[k]);
            if (!r)
                continue;
            const std::string file = fmt::format("h_{}_{}.dat", integratorName(integrator), shown[k]);
            writeSeries(dir / file, r->series, false);
            const double shade = shadeOf(k, typical, shown.size());
            line += fmt::format("'{}' with lines lw 1.5 lc rgb '{}' title 'dt = {}', ", file, colour(integrator, shade),
                                shown[k]);
        }
        if (exact)
            line += "'exact.dat' with lines lw 1 dt 2 lc rgb 'black' title 'exact', ";
        line += fmt::format("{} with lines lc rgb 'gray50' dt 3 title 'start height'\n", start);
        script += line;
    }
    return script + "unset multiplot\n";
}

/// Whether the energy ratios the plot shows span more than a decade and a half: then a linear
/// axis flattens all but the largest into one line at its foot.
bool spansDecades(const StudyConfig& config, const StudyResult& result, double dt)
{
    double least = std::numeric_limits<double>::infinity(), most = 0.0;
    for (CollisionResponse collision : distinctResponses(config, result))
        for (Integrator integrator : config.integrators)
            if (const ParticleResult* r = findRun(result, integrator, collision, dt))
                for (double e : r->series.energyRatio) {
                    if (std::isfinite(e) && !(e > 0.0))
                        return false; // a log axis would drop it (less the dryer's work, below nothing)
                    if (std::isfinite(e)) {
                        least = std::min(least, e);
                        most = std::max(most, e);
                    }
                }
    return most > 30.0 * least;
}

/// Integrator k's line: its colour, its own dash pattern and point type, points spaced out, so
/// that lines on the same curve (velocity Verlet and RK4 are both exact in flight, and every
/// stable method follows a rope alike) all stay visible.
std::string lineStyle(Integrator integrator, std::size_t k)
{
    static constexpr const char* kDashes[] = {"1", "(12,5)", "(4,4)", "(14,4,3,4)", "(2,3)", "(20,6)"};
    return fmt::format("with linespoints lw 2 dt {} pt {} ps 1.1 pi -{} lc rgb '{}'", kDashes[k % 6], 4 + 2 * (k % 5),
                       40 + 7 * k, colour(integrator));
}

/// The energy plot's dt: the one nearest 0.01 s among those at which the most runs stayed
/// finite, so that the plot compares methods rather than blow-ups.
double energyPlotDt(const StudyConfig& config, const StudyResult& result)
{
    const auto survivors = [&](double dt) {
        int n = 0;
        for (CollisionResponse collision : config.collisions)
            for (Integrator integrator : config.integrators)
                if (const ParticleResult* r = findRun(result, integrator, collision, dt); r && std::isnan(r->blewUpAt))
                    ++n;
        return n;
    };
    int most = 0;
    for (double dt : config.dts)
        most = std::max(most, survivors(dt));
    std::vector<double> candidates;
    for (double dt : config.dts)
        if (survivors(dt) == most)
            candidates.push_back(dt);
    return closest(candidates, 0.01);
}

std::string energyPlot(const std::filesystem::path& dir, const StudyConfig& config, const StudyResult& result)
{
    const double dt = energyPlotDt(config, result);
    const auto responses = distinctResponses(config, result);
    const bool collides = anyCollision(result);
    const bool exactKept = firstExact(config).has_value(); // the first moving particle's motion known
    const std::string what = std::string(result.followsSystem ? "total energy (every body)" : "energy") +
                             (result.lessSourceWork ? " less the work of the dryer" : "");
    std::string script = fmt::format("set terminal pngcairo size {},500 font 'sans,10'\nset output 'energy.png'\n"
                                     "set multiplot layout 1,{} title '{} over its start value, dt = {} s'\n"
                                     "set xlabel 't (s)'\nset ylabel 'E / E0'\nset key inside top left\n",
                                     responses.size() == 1 ? 900 : 1400, responses.size(), what, dt);
    if (spansDecades(config, result, dt))
        script += "set logscale y\nset format y '10^{%L}'\nset grid\n";
    for (CollisionResponse collision : responses) {
        std::string line = collides ? fmt::format("set title '{} response'\nplot ", collisionResponseName(collision))
                                    : std::string("unset title\nplot ");
        // The exact motion keeps its start energy only where the scene has one we know (a drop
        // with e = 1, an undamped spring); elsewhere the line is the start's, not the truth.
        line += fmt::format("1 with lines lc rgb 'gray50' dt 3 title '{}', ",
                            !result.followsSystem && exactKept ? "exact" : "start energy");
        for (std::size_t k = 0; k < config.integrators.size(); ++k) {
            const Integrator integrator = config.integrators[k];
            const ParticleResult* r = findRun(result, integrator, collision, dt);
            if (!r)
                continue;
            const std::string file = fmt::format("e_{}_{}.dat", integratorName(integrator), collisionResponseName(collision));
            writeSeries(dir / file, r->series, true);
            const std::string end = std::isnan(r->blewUpAt) ? "" : fmt::format(" (blew up at {:.3g} s)", r->blewUpAt);
            line += fmt::format("'{}' {} title '{}{}', ", file, lineStyle(integrator, k), integratorName(integrator), end);
        }
        script += line.substr(0, line.size() - 2) + "\n";
    }
    return script + "unset multiplot\nunset logscale\nunset grid\nset format y '%g'\n";
}

std::string convergencePlot(const std::filesystem::path& dir, const StudyResult& result)
{
    std::string plot;
    for (const auto& o : result.orders) {
        const std::string file = fmt::format("order_{}.dat", integratorName(o.integrator));
        std::ofstream out(dir / file);
        for (std::size_t i = 0; i < o.dts.size(); ++i)
            if (o.errors[i] > 0)
                out << o.dts[i] << ' ' << o.errors[i] << '\n';
        const std::string order = std::isnan(o.measured) ? std::string("order not measured: fewer than two dt in range")
                                                         : fmt::format("measured order {:.2f}", o.measured);
        plot += fmt::format("'{}' with linespoints lw 2 pt 7 ps 0.8 lc rgb '{}' title '{} ({})', ", file,
                            colour(o.integrator), integratorName(o.integrator), order);
    }
    // The dt axis spans the dt measured, with a margin; a single dt gets a decade around it.
    const std::vector<double> dts = result.orders.empty() ? std::vector<double>{} : result.orders.front().dts;
    const std::string xrange = dts.size() == 1 ? fmt::format("set xrange [{}:{}]\nset xtics add ('{}' {})\n", dts.front() / 3,
                                                                         dts.front() * 3, dts.front(), dts.front())
                                               : "set autoscale xfix\nset offsets graph 0.04, graph 0.04, 0, 0\n";
    // The legend goes under the plot, so the plot keeps the picture's width.
    return "set terminal pngcairo size 900,800 font 'sans,11'\nset output 'convergence.png'\n"
           "set title \"position error against dt on the spring (harmonic oscillator)\"\n"
           "set logscale xy\nset format y '10^{%L}'\nset xlabel 'dt (s)'\nset ylabel 'max position error over 2 s (m)'\n"
           "set grid\n" + xrange + "set key below maxrows 4\nplot " +
           plot +
           "0.5*x with lines dt 2 lc rgb 'gray40' title 'slope 1', 0.5*x**2 with lines dt 3 lc rgb 'gray40' title "
           "'slope 2', 0.02*x**4 with lines dt 4 lc rgb 'gray40' title 'slope 4'\n";
}

/// The bound a stable run stays under, for the plot's key.
std::string boundText(double factor) { return fmt::format("bound: {:g} E_0", factor); }

/// A method stable at every dt: a line per omega dt of its ladder, darker for the smaller.
std::string ladderLines(const std::filesystem::path& dir, const StabilityResult& s, double omega)
{
    std::string line;
    const std::string name(integratorName(s.integrator));
    for (std::size_t k = 0; k < s.ladder.size(); ++k) {
        const StabilityRun& run = s.ladder[k];
        const std::string file = fmt::format("s_{}_ladder{}.dat", name, k);
        std::ofstream out(dir / file);
        for (std::size_t i = 0; i < run.series.t.size(); ++i)
            out << run.series.t[i] * omega / (2.0 * std::numbers::pi) << ' ' << run.series.energyRatio[i] << '\n';
        const double shade = -0.5 + double(k) / double(std::max<std::size_t>(1, s.ladder.size() - 1));
        line += fmt::format("'{}' with lines lw 2 lc rgb '{}' title 'ω dt = {:g}{}', ", file, colour(s.integrator, shade),
                            run.dt * omega, run.stable ? "" : run.leftLinearRegime ? " (a spring leaves (0, 2L))"
                                                                                   : " (crosses the bound)");
    }
    return line;
}

/// One panel per integrator: E/E0 against time in periods of the highest mode, on a log scale,
/// at dt just below the measured limit (the integrator's colour, darker) and just above it
/// (lighter, dashed, ending where it crosses the bound).
std::string stabilityPlot(const std::filesystem::path& dir, const StudyConfig& config, const StudyResult& result)
{
    const double omega = *result.omegaMax;
    const double factor = config.stability.energyFactor;
    // The convergence plot before this one leaves log axes (and, for one dt, an extra x tic) set:
    // start from plain ones. The y range stops short of RK4's decay just below its limit, which
    // would squeeze the rest.
    std::string script =
        multiplot(result.stability.size(), kStabilityPlotFile,
                  fmt::format("E / E_0 just below and just above each measured stability limit ({:g}% either side), "
                              "ω_{{max}} = {:.4g} rad/s",
                              100 * kStabilityMargin, omega),
                  560) +
        fmt::format("unset logscale\nunset xtics\nset xtics\nset logscale y\nset format y '10^{{%L}}'\nset format x '%g'\n"
                    "set yrange [1e-3:{}]\nset xrange [0:{}]\nset grid\nset offsets 0, 0, 0, 0\n"
                    "set xlabel 't / (2π / ω_{{max}})   (periods of the highest mode)'\nset ylabel 'E / E_0'\n"
                    "set key below width 2\n",
                    factor * 30.0, config.stability.periods);
    for (const auto& s : result.stability) {
        const std::string name(integratorName(s.integrator));
        const std::string theory = std::isnan(s.theoryDt)   ? std::string("theory: none, gains energy at every dt")
                                   : std::isinf(s.theoryDt) ? std::string("theory: stable at every dt")
                                                            : fmt::format("theory {:.4g} s", s.theoryDt);
        const std::string measured = std::isnan(s.measuredDt) ? std::string("limit not measured")
                                                              : fmt::format("limit measured {:.4g} s", s.measuredDt);
        script += fmt::format("set title '{}: {}, {}'\nplot ", name, measured, theory);
        if (std::isnan(s.measuredDt) && s.below.series.t.empty()) {
            script += fmt::format("1 with lines lc rgb 'gray50' dt 3 title 'not measured: {}'\n", s.unmeasured);
            continue;
        }
        std::string line;
        if (!s.ladder.empty()) {
            script += ladderLines(dir, s, omega) +
                      fmt::format("{} with lines lc rgb 'gray30' dt 2 title '{}', 1 with lines lc rgb 'gray60' dt 3 "
                                  "title 'E_0'\n",
                                  factor, boundText(factor));
            continue;
        }
        for (const auto* run : {&s.below, &s.above}) {
            const bool below = run == &s.below;
            const std::string file = fmt::format("s_{}_{}.dat", name, below ? "below" : "above");
            std::ofstream out(dir / file);
            for (std::size_t i = 0; i < run->series.t.size(); ++i)
                out << run->series.t[i] * omega / (2.0 * std::numbers::pi) << ' ' << run->series.energyRatio[i] << '\n';
            // Above a measured limit a stable run means the stability is not monotone in dt there.
            const std::string verdict = run->stable ? (below || std::isnan(s.measuredDt) ? "stable"
                                                                                         : "stable again: not monotone in dt")
                                        : run->leftLinearRegime ? "a spring leaves (0, 2L)"
                                                                : "crosses the bound";
            line += fmt::format("'{}' with lines {} lc rgb '{}' title 'dt = {:.4g} s, ω dt = {:.3g} ({})', ", file,
                                below ? "lw 2" : "lw 2 dt (8,4)", colour(s.integrator, below ? -0.3 : 0.35), run->dt,
                                run->dt * omega, verdict);
        }
        script += line + fmt::format("{} with lines lc rgb 'gray30' dt 2 title '{}', 1 with lines lc rgb 'gray60' dt 3 "
                                     "title 'E_0'\n",
                                     factor, boundText(factor));
    }
    return script + "unset multiplot\n";
}

} // namespace

std::string plotScript(const std::filesystem::path& dir, const StudyConfig& config, const StudyResult& result)
{
    std::string script = heightPlot(dir, config, result) + energyPlot(dir, config, result) + convergencePlot(dir, result);
    if (!result.stability.empty())
        script += stabilityPlot(dir, config, result);
    return script;
}

} // namespace pba::study
