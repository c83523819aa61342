#include "rotation_plots.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "render/palette.hpp"

namespace pba::study {

namespace {

std::string colour(Integrator integrator, double shade = 0.0)
{
    return palette::hex(palette::shade(palette::integratorRgb(integrator), shade));
}

const RotationRun* findRun(const RotationResult& result, Integrator integrator, double dt)
{
    for (const RotationRun& r : result.runs)
        if (r.integrator == integrator && r.dt == dt)
            return &r;
    return nullptr;
}

/// One log-log panel of a measure against dt, a line per integrator (only the positive values:
/// a drift of exactly zero has no logarithm).
std::string againstDt(const std::filesystem::path& dir, const RotationConfig& config, const RotationResult& result,
                      const std::string& stem, const std::string& title, double (*measure)(const RotationRun&, double))
{
    std::string lines;
    for (Integrator integrator : config.integrators) {
        const std::string file = fmt::format("{}_{}.dat", stem, integratorName(integrator));
        std::ofstream out(dir / file);
        int points = 0;
        for (double dt : config.dts)
            if (const RotationRun* r = findRun(result, integrator, dt); r && std::isnan(r->blewUpAt))
                if (const double y = measure(*r, result.exactPeriod); y > 0.0 && std::isfinite(y)) {
                    out << dt << ' ' << y << '\n';
                    ++points;
                }
        // gnuplot refuses a file with no point on a log scale: such a line (every run blew up, or
        // kept the measure exactly) is left out of the panel and named in the key's title.
        if (points > 0)
            // A dash pattern and a point shape of its own: methods that drift alike (forward and
            // semi-implicit Euler, both explicit in the rotation) draw one line over another.
            lines += fmt::format("'{}' with linespoints lw 2 dt {} pt {} ps 0.9 lc rgb '{}' title '{}', ", file,
                                 1 + int(integrator) % 5, 4 + 2 * int(integrator), colour(integrator),
                                 integratorName(integrator));
    }
    if (lines.empty()) // a panel with nothing to draw still draws its frame
        return fmt::format("set title '{} (no run to draw)'\nset xrange [{}:{}]\nset yrange [1e-16:1]\nplot 1e-99 notitle\n"
                           "set autoscale\n", title, config.dts.front() / 2.0, config.dts.back() * 2.0);
    return fmt::format("set title '{}'\nplot ", title) + lines.substr(0, lines.size() - 2) + "\n";
}

std::string driftPlot(const std::filesystem::path& dir, const RotationConfig& config, const RotationResult& result)
{
    return "set terminal pngcairo size 1400,520 font 'sans,10'\nset output 'drift.png'\n"
           "set multiplot layout 1,2 title 'largest drift over the run against dt (left out: runs that blew up, and methods that kept it exactly)'\n"
           "set logscale xy\nset format y '10^{%T}'\nset xlabel 'dt (s)'\nset key bottom right\n"
           "set ylabel 'max |E/E0 - 1|'\n" +
           againstDt(dir, config, result, "energy", "energy", [](const RotationRun& r, double) { return r.maxEnergyDrift; }) +
           "set ylabel 'max ||L|/|L0| - 1|'\n" +
           againstDt(dir, config, result, "momentum", "angular momentum |L| (conserved without torques)",
                     [](const RotationRun& r, double) { return r.maxMomentumDrift; }) +
           "unset multiplot\nunset logscale\nset format y '%g'\n";
}

std::string periodPlot(const std::filesystem::path& dir, const RotationConfig& config, const RotationResult& result)
{
    return fmt::format("set terminal pngcairo size 900,520 font 'sans,10'\nset output '{}'\nset logscale xy\n"
                       "set format y '10^{{%T}}'\nset xlabel 'dt (s)'\nset ylabel '|T - T_{{exact}}| / T_{{exact}}'\n"
                       "set key bottom right\n",
                       kPeriodPlotFile) +
           againstDt(dir, config, result, "period",
                     fmt::format("flip period against the elliptic integral: T_{{exact}} = {:.4f} s", result.exactPeriod),
                     [](const RotationRun& r, double exact) { return std::abs(r.flipPeriod / exact - 1.0); }) +
           "unset logscale\nset format y '%g'\n";
}

/// The angular velocity about the intermediate axis against time: a panel per integrator, its
/// smallest dt darker and a large one lighter.
std::string flipPlot(const std::filesystem::path& dir, const RotationConfig& config, const RotationResult& result)
{
    std::vector<double> shown{config.dts.front()};
    for (double target : {0.01, 0.05}) {
        const double dt = *std::min_element(config.dts.begin(), config.dts.end(), [&](double a, double b) {
            return std::abs(std::log(a / target)) < std::abs(std::log(b / target));
        });
        if (std::find(shown.begin(), shown.end(), dt) == shown.end())
            shown.push_back(dt);
    }
    const std::size_t n = config.integrators.size();
    const std::size_t columns = n == 1 ? 1 : 2, rows = (n + columns - 1) / columns;
    std::string script = fmt::format(
        "set terminal pngcairo size {},{} font 'sans,10'\nset output 'flip.png'\nset multiplot layout {},{} title "
        "ARG1.': angular velocity about its intermediate axis (body frame): each sign change is {}'\n"
        "set xlabel 't (s)'\nset ylabel 'omega (rad/s)'\nset key outside right\n",
        columns == 1 ? 900 : 1400, 380 * rows + 40, rows, columns, result.flips ? "a flip" : "half a wobble");
    for (Integrator integrator : config.integrators) {
        std::string line = fmt::format("set title '{}'\nplot ", integratorName(integrator));
        bool drawn = false;
        for (std::size_t k = 0; k < shown.size(); ++k) {
            const RotationRun* r = findRun(result, integrator, shown[k]);
            if (!r || r->t.empty()) // one that blew up before its first sample has no line
                continue;
            drawn = true;
            const std::string file = fmt::format("w_{}_{}.dat", integratorName(integrator), shown[k]);
            std::ofstream out(dir / file);
            for (std::size_t i = 0; i < r->t.size(); ++i)
                out << r->t[i] << ' ' << r->intermediateOmega[i] << '\n';
            const double shade = shown.size() == 1 ? 0.0 : -0.45 + 0.9 * double(k) / double(shown.size() - 1);
            line += fmt::format("'{}' with lines lw 1.5 lc rgb '{}' title 'dt = {}', ", file, colour(integrator, shade),
                                shown[k]);
        }
        // gnuplot fails on a plot of empty files: a panel whose every run blew up at once
        // draws its frame, with a line off its range.
        script += drawn ? line.substr(0, line.size() - 2) + "\n"
                        : fmt::format("set title '{} (every run blew up before its first sample)'\nset xrange [0:{}]\n"
                                      "set yrange [-1:1]\nplot 1e99 notitle\nset autoscale\n",
                                      integratorName(integrator), config.duration);
    }
    return script + "unset multiplot\n";
}

} // namespace

std::string rotationPlotScript(const std::filesystem::path& dir, const RotationConfig& config,
                               const RotationResult& result)
{
    std::string script = driftPlot(dir, config, result);
    if (result.intermediateAxis >= 0) // a body with two equal moments has no intermediate axis to follow
        script += flipPlot(dir, config, result);
    if (!std::isnan(result.exactPeriod))
        script += periodPlot(dir, config, result);
    return script;
}

} // namespace pba::study
