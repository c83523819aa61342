#pragma once
#include <vector>

#include "pba/math.hpp"

namespace pba::study {

/// One particle's (or one world's) time series, thinned to at most a few thousand samples for
/// plotting.
struct Series {
    std::vector<double> t, y, energyRatio;
    /// A system's centre of mass at each t (a study that follows a whole system, see
    /// StudyResult::followsSystem); empty otherwise.
    std::vector<dvec3> centre;
};

} // namespace pba::study
