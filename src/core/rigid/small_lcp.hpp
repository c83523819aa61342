#pragma once
// A small dense mixed linear complementarity problem, solved exactly: find x with w = A x + b,
// w = 0 on the first `equalities` rows (x free there) and x >= 0, w >= 0, x . w = 0 on the others.
// The collision pass's blows on a pinned body or a jointed mechanism solve their normal pushes so
// (a handful of rows, with the joints' as equalities), where sweeps converge too slowly on a long
// lever.
#include <cstddef>
#include <vector>

namespace pba::rigid {

/// `a` is n x n, row-major, symmetric and positive semi-definite (a blow's rows: J M^-1 J^T).
/// Active sets: every row pushes, then the most negative push leaves and the most violated
/// speed joins, one at a time, until neither is left (at most 4n + 4 rounds); the equalities
/// are always active. `tolerance` is the speed below zero that counts as violated.
void solveSmallLcp(const std::vector<double>& a, const std::vector<double>& b, std::size_t n, double tolerance,
                   std::vector<double>& x, std::size_t equalities = 0);

} // namespace pba::rigid
