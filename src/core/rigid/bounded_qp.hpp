#pragma once
// A convex quadratic program with bounds, solved to a tolerance without forming its matrix:
// minimise f(y) = y.A y / 2 + c.y subject to lower <= y <= upper, A symmetric positive
// semi-definite and given only as its product with a vector. With no upper bound its optimum is
// the LCP w = A y + c, y >= lower, w >= 0, (y - lower).w = 0: a contact island's normal impulses,
// whatever its size; with both, its friction impulses within bounds the normal ones set.
//
// The method is Dostál's MPRGP (modified proportioning with reduced gradient projections):
// conjugate gradients over the rows off their bounds while the free gradient dominates, a
// projected step along it when a step would cross a bound, and a proportioning step that frees
// the bound rows pulling away. Unlike sweeps, its rate does not depend on the ratio of the
// masses a push passes between, only on the scaled matrix's conditioning.
// Private to the core.
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

namespace pba::rigid {

/// out = A in; called once or twice an iteration.
using QpProduct = std::function<void(std::span<const double> in, std::span<double> out)>;

struct BoundedQpResult {
    int iterations = 0;
    double projectedGradient = 0.0; ///< the optimality error left: |w| on free rows, w's negative part on bound ones
};

/// `y` is the start on entry (within the bounds; an upper bound may be infinite) and the optimum
/// on return, to `tolerance` in the projected gradient or after `maxIterations` products.
/// `largestEigenvalue` bounds A's from above within a factor of two (the projected steps' length
/// is its inverse).
BoundedQpResult solveBoundedQp(const QpProduct& multiply, std::span<const double> c, std::span<const double> lower,
                               std::span<const double> upper, double largestEigenvalue, double tolerance,
                               int maxIterations, std::span<double> y);

/// A's largest eigenvalue by power iteration from a vector of ones (a few products: A's entries
/// are positive along a stack, so the start is close).
double largestEigenvalue(const QpProduct& multiply, std::size_t n, int iterations = 12);

} // namespace pba::rigid
