#include "xpbd.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace pba::detail {

namespace {

constexpr std::size_t kGrain = 2048;

template <class F>
void forEach(std::size_t n, F&& fn)
{
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i)
            fn(i);
    });
}

} // namespace

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
    m_order.resize(springs.size());
    std::vector<std::uint32_t> next(m_colourStart.begin(), m_colourStart.end() - 1);
    for (std::size_t s = 0; s < springs.size(); ++s)
        m_order[next[colour[s]]++] = static_cast<std::uint32_t>(s);
}

void Xpbd::step(const SpringSystem& springs, std::span<const double> mass, std::span<dvec3> x, std::span<dvec3> v,
                double dt, int substeps, const External& external)
{
    const std::size_t n = x.size();
    const double h = dt / double(substeps);
    m_inverseMass.resize(n);
    m_start.resize(n);
    m_accel.resize(n);
    forEach(n, [&](std::size_t p) { m_inverseMass[p] = 1.0 / mass[p]; });
    for (int sub = 0; sub < substeps; ++sub) {
        external(x, v, m_accel);
        forEach(n, [&](std::size_t p) {
            v[p] += h * m_accel[p];
            m_start[p] = x[p];
            x[p] += h * v[p];
        });
        project(springs, x, h);
        forEach(n, [&](std::size_t p) { v[p] = (x[p] - m_start[p]) / h; });
    }
}

void Xpbd::project(const SpringSystem& springs, std::span<dvec3> x, double h)
{
    for (std::size_t c = 0; c + 1 < m_colourStart.size(); ++c) {
        const std::size_t begin = m_colourStart[c];
        forEach(m_colourStart[c + 1] - begin, [&](std::size_t k) {
            const std::uint32_t s = m_order[begin + k];
            const double stiffness = springs.stiffness(s);
            if (!(stiffness > 0.0))
                return; // no stiffness, no constraint
            const std::uint32_t a = springs.a(s), b = springs.b(s);
            const bool fixed = b == SpringSystem::kFixed;
            const dvec3 xb = fixed ? springs.fixedPoint(s) : x[b];
            const dvec3 d = xb - x[a];
            const double length = glm::length(d);
            if (!(length > 0.0))
                return; // no direction to pull along
            const dvec3 u = d / length;
            const double wa = m_inverseMass[a], wb = fixed ? 0.0 : m_inverseMass[b];
            const double compliance = 1.0 / (stiffness * h * h); // alpha~ = alpha / h^2, alpha = 1 / k
            const double gamma = springs.damping(s) / (stiffness * h);
            const dvec3 moved = (fixed ? dvec3(0.0) : xb - m_start[b]) - (x[a] - m_start[a]);
            const double dl = (-(length - springs.restLength(s)) - gamma * glm::dot(u, moved)) /
                              ((1.0 + gamma) * (wa + wb) + compliance);
            x[a] -= (wa * dl) * u;
            if (!fixed)
                x[b] += (wb * dl) * u;
        });
    }
}

} // namespace pba::detail
