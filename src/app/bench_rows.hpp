#pragma once
// `pba bench`'s rows of swarm rates, and how they are printed: the table, and a note where a row's
// windows spread more than the machine's steady speed explains.
#include <cstddef>
#include <string>
#include <vector>

namespace pba::app::bench {

/// A line of the rows' table: a layout (the bound, the heap-Particle baseline, the swarm), its
/// integrator and phase, and its rate over its windows.
struct Row {
    std::string layout;
    std::string integrator;
    std::string phase; ///< one of kPhases' names for the swarm and the baseline, empty for the bound
    std::size_t n = 0;
    int threads = 1;
    double rate = 0.0; ///< particle-steps per second: the best window (see measureSize)
    double bytesPerParticle = 0.0;
    double ofBound = 0.0;
    double ofBaseline = 0.0;
    double medianRate = 0.0;     ///< the median window, for how far the machine's speed swung
};

/// The rows as a table, one line each.
std::string table(const std::vector<Row>& rows);

/// A line for each size where some row's best window is more than kLevelSpread times its
/// median (the machine's speed changed level during the run, which a ratio of best windows
/// hides); empty when every row held steady.
std::string spreadNotes(const std::vector<Row>& rows);

} // namespace pba::app::bench
