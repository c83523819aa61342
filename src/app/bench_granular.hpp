#pragma once
// `pba bench`'s granular rows: a swarm of colliding grains (the granular scene's grains, as many
// as asked, spread over a floor sized to them) stepped with its contacts and, in the same run,
// without them.
#include <cstddef>
#include <vector>

namespace pba::app::bench {

struct GranularRow {
    std::size_t n = 0;
    int threads = 1;
    double rate = 0.0;              ///< particle-steps per second with the grains' contacts (best window)
    double withoutCollisions = 0.0; ///< the same swarm without them, windows taken in turn with it
    double medianRate = 0.0, medianWithout = 0.0;
};

/// The sizes of the rows; with --quick only the first.
inline constexpr std::size_t kGranularSizes[] = {100000, 1000000};

/// One row per size on all cores: windows of minTime, `repeats` of each, in turn.
std::vector<GranularRow> measureGranular(bool quick, double minTime, int repeats, int cores);

} // namespace pba::app::bench
