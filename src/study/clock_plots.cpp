#include "clock_plots.hpp"

#include <cmath>
#include <fstream>

#include <fmt/format.h>

namespace pba::study {

namespace {

/// A clock's colour (fixed would be drawn in green, but its distances are zero: no logarithm).
const char* colour(ClockKind clock)
{
    switch (clock) {
    case ClockKind::Fixed: return "#2ca02c";
    case ClockKind::SemiFixed: return "#1f77b4";
    case ClockKind::Variable: return "#d62728";
    }
    return "#000000";
}

/// One panel, steady or through the hitch: a line per clock and rate, 30 Hz solid with circles,
/// 144 Hz dashed with triangles, so that a line on top of another stays visible.
std::string panel(const std::filesystem::path& dir, const ClockConfig& config, const ClockResult& result, bool hitch)
{
    std::string lines, zero;
    for (const ClockDrift& d : result.drifts) {
        if (d.hitch != hitch)
            continue;
        const std::string file = fmt::format("{}_{}_{}.dat", clockName(d.clock), hitch ? "hitch" : "steady", d.rate);
        std::ofstream out(dir / file);
        int points = 0;
        for (std::size_t s = 0; s < d.t.size(); ++s)
            if (d.distance[s] > 0.0 && std::isfinite(d.distance[s])) {
                out << d.t[s] << ' ' << d.distance[s] << '\n';
                ++points;
            }
        if (points == 0) { // identical (or nothing sampled): no logarithm, named in the title
            zero += fmt::format("{}{} {} Hz", zero.empty() ? "" : ", ", clockName(d.clock), d.rate);
            continue;
        }
        const bool slow = d.rate < kClockReferenceRate;
        lines += fmt::format("'{}' with linespoints lw 2 dt {} pt {} ps 0.7 lc rgb '{}' title '{} {} Hz', ", file,
                             slow ? 1 : 2, slow ? 7 : 9, colour(d.clock), clockName(d.clock), d.rate);
    }
    const std::string title = fmt::format("{}{}", hitch ? fmt::format("a {:g} s frame at t = {:g} s", kHitchSeconds, kHitchAt)
                                                        : std::string("steady frames"),
                                          zero.empty() ? "" : fmt::format(" (identical to the bit: {})", zero));
    if (lines.empty())
        return fmt::format("set title '{}'\nset xrange [0:{}]\nset yrange [1e-16:1]\nplot 1e-99 notitle\nset autoscale\n",
                           title, config.duration);
    return fmt::format("set title '{}'\nplot ", title) + lines.substr(0, lines.size() - 2) + "\n";
}

} // namespace

std::string clockPlotScript(const std::filesystem::path& dir, const ClockConfig& config, const ClockResult& result)
{
    return fmt::format("set terminal pngcairo size 1400,520 font 'sans,10'\nset output '{}'\n"
                       "set multiplot layout 1,2 title 'largest distance of a body from the 60 Hz run of the same clock "
                       "(dt = {:g} s)'\nset logscale y\nset format y '10^{{%T}}'\nset xlabel 'wall-clock time (s)'\n"
                       "set ylabel 'distance (m)'\nset key bottom right\nset grid\n",
                       kClockPlotFile, config.dt) +
           panel(dir, config, result, false) + panel(dir, config, result, true) + "unset multiplot\n";
}

} // namespace pba::study
