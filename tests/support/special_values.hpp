#pragma once
// The values that bad input is made of.
#include <limits>

namespace pba::test {
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();
} // namespace pba::test
