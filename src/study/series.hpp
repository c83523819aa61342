#pragma once
#include <vector>

namespace pba::study {

/// One particle's (or one world's) time series, thinned to at most a few thousand samples for
/// plotting.
struct Series {
    std::vector<double> t, y, energyRatio;
};

} // namespace pba::study
