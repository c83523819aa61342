#include "rigid/bounded_qp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pba::rigid {

namespace {

double dot(std::span<const double> a, std::span<const double> b)
{
    double s = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        s += a[i] * b[i];
    return s;
}

/// The gradient's parts: on a row off its bound all of it (free), on a row at its bound only a
/// pull away from it (chopped).
struct Gradients {
    std::vector<double> free, chopped;
    double freeSquared = 0.0, choppedSquared = 0.0, reducedDotFree = 0.0;

    void split(std::span<const double> y, std::span<const double> g, std::span<const double> lower,
               std::span<const double> upper, double step)
    {
        free.assign(y.size(), 0.0);
        chopped.assign(y.size(), 0.0);
        freeSquared = choppedSquared = reducedDotFree = 0.0;
        for (std::size_t i = 0; i < y.size(); ++i) {
            if (y[i] <= lower[i])
                chopped[i] = std::min(g[i], 0.0);
            else if (y[i] >= upper[i])
                chopped[i] = std::max(g[i], 0.0);
            else {
                free[i] = g[i];
                freeSquared += g[i] * g[i];
                // The reduced free gradient: no further than a bound in one projected step.
                const double room = g[i] > 0.0 ? (y[i] - lower[i]) / step : (upper[i] - y[i]) / step;
                const double reduced = g[i] > 0.0 ? std::min(room, g[i]) : std::max(-room, g[i]);
                reducedDotFree += reduced * g[i];
            }
            choppedSquared += chopped[i] * chopped[i];
        }
    }
};

} // namespace

double largestEigenvalue(const QpProduct& multiply, std::size_t n, int iterations)
{
    std::vector<double> v(n, 1.0 / std::sqrt(double(std::max<std::size_t>(n, 1)))), av(n);
    double lambda = 0.0;
    for (int k = 0; k < iterations; ++k) {
        multiply(v, av);
        const double length = std::sqrt(dot(av, av));
        if (length == 0.0)
            return 0.0;
        lambda = length;
        for (std::size_t i = 0; i < n; ++i)
            v[i] = av[i] / length;
    }
    return lambda;
}

BoundedQpResult solveBoundedQp(const QpProduct& multiply, std::span<const double> c, std::span<const double> lower,
                               std::span<const double> upper, double largestEigenvalue, double tolerance,
                               int maxIterations, std::span<double> y)
{
    const std::size_t n = y.size();
    BoundedQpResult result;
    if (n == 0 || largestEigenvalue <= 0.0)
        return result;
    const double step = 1.0 / largestEigenvalue; // within (0, 2 / ||A||]
    std::vector<double> g(n), p(n), ap(n);
    const auto gradient = [&] {
        multiply(y, g);
        for (std::size_t i = 0; i < n; ++i)
            g[i] += c[i];
        ++result.iterations;
    };
    gradient();
    Gradients parts;
    parts.split(y, g, lower, upper, step);
    p = parts.free;
    while (result.iterations < maxIterations) {
        result.projectedGradient = std::sqrt(parts.freeSquared + parts.choppedSquared);
        if (result.projectedGradient <= tolerance)
            break;
        if (parts.choppedSquared > parts.reducedDotFree) {
            // Proportioning: the rows at their bounds that pull away leave them together (a
            // row at its upper bound has a chopped gradient of the other sign: it moves down).
            multiply(parts.chopped, ap);
            ++result.iterations;
            const double curvature = dot(parts.chopped, ap);
            if (curvature <= 0.0)
                break;
            double alpha = dot(g, parts.chopped) / curvature;
            for (std::size_t i = 0; i < n; ++i) // never past the other bound
                if (parts.chopped[i] > 0.0)
                    alpha = std::min(alpha, (y[i] - lower[i]) / parts.chopped[i]);
                else if (parts.chopped[i] < 0.0)
                    alpha = std::min(alpha, (y[i] - upper[i]) / parts.chopped[i]);
            for (std::size_t i = 0; i < n; ++i) {
                y[i] -= alpha * parts.chopped[i];
                g[i] -= alpha * ap[i];
            }
            parts.split(y, g, lower, upper, step);
            p = parts.free;
            continue;
        }
        multiply(p, ap);
        ++result.iterations;
        const double curvature = dot(p, ap);
        if (curvature <= 0.0)
            break;
        const double alphaCg = dot(g, p) / curvature;
        double alphaFeasible = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < n; ++i)
            if (p[i] > 0.0)
                alphaFeasible = std::min(alphaFeasible, (y[i] - lower[i]) / p[i]);
            else if (p[i] < 0.0)
                alphaFeasible = std::min(alphaFeasible, (y[i] - upper[i]) / p[i]);
        if (alphaCg <= alphaFeasible) {
            // A conjugate-gradient step within the bounds.
            for (std::size_t i = 0; i < n; ++i) {
                y[i] -= alphaCg * p[i];
                g[i] -= alphaCg * ap[i];
            }
            parts.split(y, g, lower, upper, step);
            const double beta = dot(parts.free, ap) / curvature;
            for (std::size_t i = 0; i < n; ++i)
                p[i] = parts.free[i] - beta * p[i];
            continue;
        }
        // Expansion: up to the first bound, then a projected step along the free gradient.
        for (std::size_t i = 0; i < n; ++i) {
            y[i] -= alphaFeasible * p[i];
            g[i] -= alphaFeasible * ap[i];
        }
        parts.split(y, g, lower, upper, step);
        for (std::size_t i = 0; i < n; ++i)
            y[i] = std::clamp(y[i] - step * parts.free[i], lower[i], upper[i]);
        gradient();
        parts.split(y, g, lower, upper, step);
        p = parts.free;
    }
    result.projectedGradient = std::sqrt(parts.freeSquared + parts.choppedSquared);
    return result;
}

} // namespace pba::rigid
