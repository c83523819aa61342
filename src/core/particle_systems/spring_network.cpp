#include "pba/spring_network.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "pba/body.hpp"
#include "pba/forces.hpp"
#include "forces/spring_force.hpp"

namespace pba {

namespace {

/// Springs and bodies a task: enough work that a thread's start is paid for.
constexpr std::size_t kGrain = 4096;

} // namespace

SpringNetwork::SpringNetwork(const std::vector<Link>& links)
{
    std::size_t lowest = links.empty() ? 0 : links.front().a, highest = lowest;
    if (links.size() >= (std::size_t(1) << 31))
        throw std::invalid_argument(fmt::format("a spring network holds fewer than 2^31 springs, not {}", links.size()));
    for (const Link& l : links) {
        if (l.a == l.b)
            throw std::invalid_argument(fmt::format("a spring joins body {} to itself", l.a));
        if (std::max(l.a, l.b) > std::numeric_limits<std::uint32_t>::max())
            throw std::invalid_argument(fmt::format("a spring network joins bodies numbered below 2^32, not {}",
                                                    std::max(l.a, l.b)));
        m_a.push_back(static_cast<std::uint32_t>(l.a));
        m_b.push_back(static_cast<std::uint32_t>(l.b));
        m_stiffness.push_back(l.stiffness);
        m_restLength.push_back(l.restLength);
        m_damping.push_back(l.damping);
        m_damped = m_damped || l.damping > 0.0;
        lowest = std::min({lowest, l.a, l.b});
        highest = std::max({highest, l.a, l.b});
    }
    m_lowest = lowest;
    // The incidence list by counting sort: body p's springs in the springs' order.
    const std::size_t bodies = links.empty() ? 0 : highest - lowest + 1;
    m_first.assign(bodies + 1, 0);
    for (std::size_t s = 0; s < size(); ++s) {
        ++m_first[m_a[s] - lowest + 1];
        ++m_first[m_b[s] - lowest + 1];
    }
    for (std::size_t p = 0; p < bodies; ++p)
        m_first[p + 1] += m_first[p];
    m_incident.resize(2 * size());
    std::vector<std::size_t> next(m_first.begin(), m_first.end() - 1);
    for (std::size_t s = 0; s < size(); ++s) {
        m_incident[next[m_a[s] - lowest]++] = static_cast<std::uint32_t>(2 * s);
        m_incident[next[m_b[s] - lowest]++] = static_cast<std::uint32_t>(2 * s + 1);
    }
}

void SpringNetwork::onSecondEnds(const State* states, dvec3* onSecond, std::size_t begin, std::size_t end) const
{
    // Raw pointers: a store through onSecond might otherwise change the vectors' own
    // pointers, which the compiler would then load again for every spring. (A loop vectorised
    // for AVX2, four springs at a time, measured no faster here: the pass is bound by memory,
    // the springs' arrays and the states, not by its arithmetic.)
    const std::uint32_t* a = m_a.data();
    const std::uint32_t* b = m_b.data();
    const double* stiffness = m_stiffness.data();
    const double* restLength = m_restLength.data();
    const double* damping = m_damping.data();
    for (std::size_t s = begin; s < end; ++s) {
        const State& first = states[a[s]];
        const State& second = states[b[s]];
        onSecond[s] = springForce(first.pos, stiffness[s], restLength[s], damping[s], second.pos,
                                  second.vel - first.vel);
    }
}

dvec3 SpringNetwork::force(std::size_t, const Body&, const dvec3&, const dvec3&) const { return dvec3(0.0); }

void SpringNetwork::accumulate(const BodyStates& in, Accumulators& out) const
{
    // Pass 1's output, the force on each spring's second end, goes to the caller's scratch (a
    // World keeps one, so a step allocates nothing), or to one of this call's own.
    std::vector<dvec3> own;
    std::vector<dvec3>& forces = out.scratch ? *out.scratch : own;
    forces.resize(size());
    dvec3* onSecond = forces.data();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, size(), kGrain), [&](const auto& range) {
        onSecondEnds(in.states.data(), onSecond, range.begin(), range.end());
    });
    const std::size_t bodies = m_first.empty() ? 0 : m_first.size() - 1;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bodies, kGrain), [&](const auto& range) {
        for (std::size_t p = range.begin(); p < range.end(); ++p) {
            // A fixed body's sum is made too (no one reads it): testing for it would visit every
            // body's object, the slowest memory this pass would touch.
            const std::size_t i = m_lowest + p;
            if (!in.wants(i))
                continue;
            dvec3 f(0.0);
            for (std::size_t k = m_first[p]; k < m_first[p + 1]; ++k) {
                const std::size_t end = m_incident[k];
                const double sign = double(end & 1) * 2.0 - 1.0; // the second end +1, the first -1: exact
                f += sign * onSecond[end >> 1];
            }
            out.add(i, f);
        }
    });
}

double SpringNetwork::energy(std::size_t s, const BodyStates& in) const
{
    const double stretch = glm::length(in.states[m_b[s]].pos - in.states[m_a[s]].pos) - m_restLength[s];
    return 0.5 * m_stiffness[s] * stretch * stretch;
}

double SpringNetwork::potentialEnergyShare(std::size_t index, const BodyStates& in) const
{
    if (index < m_lowest || index + 1 >= m_lowest + m_first.size())
        return 0.0;
    const std::size_t p = index - m_lowest;
    double e = 0.0;
    for (std::size_t k = m_first[p]; k < m_first[p + 1]; ++k)
        e += 0.5 * energy(m_incident[k] >> 1, in);
    return e;
}

double SpringNetwork::totalPotentialEnergy(const BodyStates& in) const
{
    double e = 0.0;
    for (std::size_t s = 0; s < size(); ++s)
        e += energy(s, in);
    return e;
}

void SpringNetwork::appendCouplings(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const
{
    for (std::size_t s = 0; s < size(); ++s)
        pairs.emplace_back(m_a[s], m_b[s]);
}

} // namespace pba
