#include "bench_rows.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

namespace pba::app::bench {

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

/// This machine's bandwidth at 1e7 sits at one of two levels, about 75 or 135 GB/s, for ten
/// seconds to a minute at a time, whatever runs (docs/performance.md, "Memory
/// bandwidth"); within a level a row's windows spread by a few percent.
constexpr double kLevelSpread = 1.25;

std::string spreadNotes(const std::vector<Row>& rows)
{
    std::map<std::size_t, double> widest; // by size, the largest best / median over its rows
    for (const Row& r : rows)
        if (r.medianRate > 0.0)
            widest[r.n] = std::max(widest[r.n], r.rate / r.medianRate);
    std::string out;
    for (const auto& [n, spread] : widest)
        if (spread > kLevelSpread)
            out += fmt::format("note: at N = {} a row's best window is {:.2f} times its median: the machine's speed "
                               "(at 1e7 its memory bandwidth) changed during the run, so an \"of bound\" holds only "
                               "where the row's best and the bound's came at the same speed; read the medians "
                               "too, or run again.\n",
                               n, spread);
    return out;
}

} // namespace pba::app::bench
