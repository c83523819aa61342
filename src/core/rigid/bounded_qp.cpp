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

namespace {

/// One solve's state: the iterate, its gradient, the search direction and their parts.
class Mprgp {
public:
    Mprgp(const QpProduct& multiply, std::span<const double> c, std::span<const double> lower,
          std::span<const double> upper, double step, std::span<double> y)
        : m_multiply(multiply), m_c(c), m_lower(lower), m_upper(upper), m_step(step), m_y(y), m_g(y.size()),
          m_ap(y.size())
    {
        gradient();
        m_p = m_parts.free;
    }

    int products() const { return m_products; }
    double projectedGradient() const { return std::sqrt(m_parts.freeSquared + m_parts.choppedSquared); }
    /// Whether the bound rows pulling away outweigh the free gradient (Dostál's proportionality).
    bool disproportional() const { return m_parts.choppedSquared > m_parts.reducedDotFree; }

    /// The rows at their bounds that pull away leave them together (a row at its upper bound has
    /// a chopped gradient of the other sign: it moves down). False where the matrix has no
    /// curvature along them.
    bool proportion()
    {
        const std::vector<double>& d = m_parts.chopped;
        const double curvature = product(d);
        if (curvature <= 0.0)
            return false;
        move(std::min(dot(m_g, d) / curvature, feasibleStep(d)), d);
        m_parts.split(m_y, m_g, m_lower, m_upper, m_step);
        m_p = m_parts.free;
        return true;
    }

    /// A conjugate-gradient step along p if it stays within the bounds; else an expansion: up to
    /// the first bound, then a projected step along the free gradient.
    bool conjugate()
    {
        const double curvature = product(m_p);
        if (curvature <= 0.0)
            return false;
        const double alpha = dot(m_g, m_p) / curvature, feasible = feasibleStep(m_p);
        if (alpha <= feasible) {
            move(alpha, m_p);
            m_parts.split(m_y, m_g, m_lower, m_upper, m_step);
            const double beta = dot(m_parts.free, m_ap) / curvature;
            for (std::size_t i = 0; i < m_p.size(); ++i)
                m_p[i] = m_parts.free[i] - beta * m_p[i];
            return true;
        }
        move(feasible, m_p);
        m_parts.split(m_y, m_g, m_lower, m_upper, m_step);
        for (std::size_t i = 0; i < m_y.size(); ++i)
            m_y[i] = std::clamp(m_y[i] - m_step * m_parts.free[i], m_lower[i], m_upper[i]);
        gradient();
        m_p = m_parts.free;
        return true;
    }

private:
    void gradient()
    {
        m_multiply(m_y, m_g);
        for (std::size_t i = 0; i < m_g.size(); ++i)
            m_g[i] += m_c[i];
        ++m_products;
        m_parts.split(m_y, m_g, m_lower, m_upper, m_step);
    }
    /// d.A d, with A d kept for the move.
    double product(std::span<const double> d)
    {
        m_multiply(d, m_ap);
        ++m_products;
        return dot(d, m_ap);
    }
    /// The longest step along -d that keeps every row within its bounds.
    double feasibleStep(std::span<const double> d) const
    {
        double alpha = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < d.size(); ++i)
            if (d[i] > 0.0)
                alpha = std::min(alpha, (m_y[i] - m_lower[i]) / d[i]);
            else if (d[i] < 0.0)
                alpha = std::min(alpha, (m_y[i] - m_upper[i]) / d[i]);
        return alpha;
    }
    /// y -= alpha d, and the gradient with it (A d is the last product's).
    void move(double alpha, std::span<const double> d)
    {
        for (std::size_t i = 0; i < m_y.size(); ++i) {
            m_y[i] -= alpha * d[i];
            m_g[i] -= alpha * m_ap[i];
        }
    }

    const QpProduct& m_multiply;
    std::span<const double> m_c, m_lower, m_upper;
    double m_step;
    std::span<double> m_y;
    std::vector<double> m_g, m_p, m_ap;
    Gradients m_parts;
    int m_products = 0;
};

} // namespace

BoundedQpResult solveBoundedQp(const QpProduct& multiply, std::span<const double> c, std::span<const double> lower,
                               std::span<const double> upper, double largestEigenvalue, double tolerance,
                               int maxIterations, std::span<double> y)
{
    BoundedQpResult result;
    if (y.empty() || largestEigenvalue <= 0.0)
        return result;
    Mprgp solve(multiply, c, lower, upper, 1.0 / largestEigenvalue, y); // a step within (0, 2 / ||A||]
    while (solve.products() < maxIterations && solve.projectedGradient() > tolerance)
        if (!(solve.disproportional() ? solve.proportion() : solve.conjugate()))
            break;
    result.iterations = solve.products();
    result.projectedGradient = solve.projectedGradient();
    return result;
}

} // namespace pba::rigid
