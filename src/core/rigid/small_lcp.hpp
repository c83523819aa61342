#pragma once
// A small dense linear complementarity problem, solved exactly: find x with x >= 0,
// w = A x + b >= 0 and x . w = 0. The collision pass's blows on a pinned body solve their normal
// pushes so (a handful of rows), where sweeps converge too slowly on a long lever.
#include <cstddef>
#include <vector>

namespace pba::rigid {

/// `a` is n x n, row-major, symmetric and positive semi-definite (a blow's rows: J M^-1 J^T).
/// Active sets: every row pushes, then the most negative push leaves and the most violated
/// speed joins, one at a time, until neither is left (at most 4n + 4 rounds). `tolerance` is the
/// speed below zero that counts as violated.
void solveSmallLcp(const std::vector<double>& a, const std::vector<double>& b, std::size_t n, double tolerance,
                   std::vector<double>& x);

} // namespace pba::rigid
