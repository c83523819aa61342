#include "xpbd.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "parallel.hpp"

namespace pba::detail {

Xpbd::Xpbd(const SpringSystem& springs)
{
    // Greedy colouring: each spring takes the lowest colour neither of its (moving) ends has yet.
    std::vector<std::vector<std::uint32_t>> used(springs.bodies());
    std::vector<std::uint32_t> colour(springs.size());
    std::uint32_t count = 0;
    for (std::size_t s = 0; s < springs.size(); ++s) {
        const std::uint32_t a = springs.a(s), b = springs.b(s);
        auto taken = [&](std::uint32_t c) {
            const auto has = [c](const std::vector<std::uint32_t>& list) {
                return std::find(list.begin(), list.end(), c) != list.end();
            };
            return has(used[a]) || (b != SpringSystem::kFixed && has(used[b]));
        };
        std::uint32_t c = 0;
        while (taken(c))
            ++c;
        colour[s] = c;
        used[a].push_back(c);
        if (b != SpringSystem::kFixed)
            used[b].push_back(c);
        count = std::max(count, c + 1);
    }
    m_colourStart.assign(count + 1, 0);
    for (const std::uint32_t c : colour)
        ++m_colourStart[c + 1];
    for (std::uint32_t c = 0; c < count; ++c)
        m_colourStart[c + 1] += m_colourStart[c];
    // A spring of no stiffness is no constraint: marked by a negative compliance, and skipped.
    m_constraints.resize(springs.size());
    std::vector<std::uint32_t> next(m_colourStart.begin(), m_colourStart.end() - 1);
    for (std::size_t s = 0; s < springs.size(); ++s) {
        const double k = springs.stiffness(s);
        m_constraints[next[colour[s]]++] = Constraint{springs.a(s), springs.b(s), static_cast<std::uint32_t>(s),
                                                      springs.restLength(s), k > 0.0 ? 1.0 / k : -1.0,
                                                      k > 0.0 ? springs.damping(s) / k : 0.0};
    }
}

void Xpbd::step(const SpringSystem& springs, std::span<const double> mass, std::span<dvec3> x, std::span<dvec3> v,
                double dt, int substeps, const External& external)
{
    const std::size_t n = x.size();
    const double h = dt / double(substeps);
    m_inverseMass.resize(n);
    m_start.resize(n);
    m_accel.resize(n);
    forEachIndex(n, [&](std::size_t p) { m_inverseMass[p] = 1.0 / mass[p]; });
    scale(h);
    for (int sub = 0; sub < substeps; ++sub) {
        external(x, v, m_accel);
        forEachIndex(n, [&](std::size_t p) {
            v[p] += h * m_accel[p];
            m_start[p] = x[p];
            x[p] += h * v[p];
        });
        if (m_stiffest > kStiff) {
            m_lambda.assign(m_constraints.size(), 0.0);
            for (int sweep = 0; sweep < kMaxSweeps && project<true>(springs, x) > kTolerance; ++sweep) {
            }
        } else {
            project<false>(springs, x);
        }
        forEachIndex(n, [&](std::size_t p) { v[p] = (x[p] - m_start[p]) / h; });
    }
}

void Xpbd::scale(double h)
{
    m_scales.resize(m_constraints.size());
    forEachIndex(m_constraints.size(), [&](std::size_t k) {
        const Constraint& con = m_constraints[k];
        if (con.inverseStiffness < 0.0) {
            m_scales[k] = Scale{};
            return;
        }
        const double wa = m_inverseMass[con.a], wb = con.b == SpringSystem::kFixed ? 0.0 : m_inverseMass[con.b];
        const double gamma = con.dampingOverStiffness / h;
        const double denominator = (1.0 + gamma) * (wa + wb) + con.inverseStiffness / (h * h); // alpha~ = alpha / h^2
        m_scales[k] = Scale{wa / denominator, wb / denominator, gamma, con.inverseStiffness / (h * h), 1.0 / denominator};
    });
    m_stiffest = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, m_constraints.size(), kIndexGrain), 0.0,
        [&](const tbb::blocked_range<std::size_t>& r, double most) {
            for (std::size_t k = r.begin(); k < r.end(); ++k)
                if (m_scales[k].compliance > 0.0)
                    most = std::max(most, (m_scales[k].a + m_scales[k].b) / (m_scales[k].inverseDenominator * m_scales[k].compliance));
            return most;
        },
        [](double p, double q) { return std::max(p, q); });
}

template <bool kSweeps>
double Xpbd::project(const SpringSystem& springs, std::span<dvec3> x)
{
    const Constraint* constraints = m_constraints.data();
    const Scale* scales = m_scales.data();
    const dvec3* start = m_start.data();
    double* lambda = m_lambda.data();
    dvec3* positions = x.data();
    double largest = 0.0;
    for (std::size_t c = 0; c + 1 < m_colourStart.size(); ++c) {
        const std::size_t begin = m_colourStart[c];
        const double colourLargest = tbb::parallel_reduce(
            tbb::blocked_range<std::size_t>(begin, m_colourStart[c + 1], kIndexGrain), 0.0,
            [&](const tbb::blocked_range<std::size_t>& r, double worst) {
                for (std::size_t k = r.begin(); k < r.end(); ++k) {
                    const Constraint& con = constraints[k];
                    const Scale& scale = scales[k];
                    const bool fixed = con.b == SpringSystem::kFixed;
                    const dvec3 xa = positions[con.a];
                    const dvec3 xb = fixed ? springs.fixedPoint(con.spring) : positions[con.b];
                    const dvec3 d = xb - xa;
                    const double length = glm::length(d);
                    if (!(length > 0.0) || con.inverseStiffness < 0.0)
                        continue; // no direction to pull along, or no constraint
                    // The constraint's error C - alpha~ lambda and its damping term gamma grad C . (x* - x), along u = d / |d|.
                    double error = length - con.restLength - (kSweeps ? scale.compliance * lambda[k] : 0.0);
                    if (scale.gamma != 0.0) {
                        const dvec3 moved = (fixed ? dvec3(0.0) : xb - start[con.b]) - (xa - start[con.a]);
                        error += scale.gamma * glm::dot(d, moved) / length;
                    }
                    if (kSweeps) {
                        lambda[k] += error * scale.inverseDenominator;
                        worst = std::max(worst, std::abs(error) / (con.restLength > 0.0 ? con.restLength : 1.0));
                    }
                    const dvec3 pull = d * (error / length);
                    positions[con.a] = xa + scale.a * pull;
                    if (!fixed)
                        positions[con.b] = xb - scale.b * pull;
                }
                return worst;
            },
            [](double p, double q) { return std::max(p, q); });
        largest = std::max(largest, colourLargest);
    }
    return largest;
}

} // namespace pba::detail
