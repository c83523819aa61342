#include "particle_systems/spring_neighbours.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "pba/forces.hpp"
#include "pba/spring_network.hpp"

namespace pba::detail {

namespace {

/// Every spring between two bodies, with its rest length, whatever force holds it.
struct LinkCollector final : ForceVisitor {
    std::vector<SpringNetwork::Link> links;
    using ForceVisitor::visit;
    void visit(const TwoBodySpring& s) override
    {
        links.push_back({s.first(), s.second(), s.stiffness(), s.restLength(), s.damping()});
    }
    void visit(const SpringNetwork& network) override
    {
        for (std::size_t s = 0; s < network.size(); ++s)
            links.push_back(network.link(s));
    }
};

constexpr double kInfinite = std::numeric_limits<double>::infinity();

} // namespace

void SpringNeighbours::update(const std::vector<ClonePtr<Force>>& forces, std::span<const double> radii)
{
    if (m_made && forces.size() == m_forces && std::equal(radii.begin(), radii.end(), m_radii.begin(), m_radii.end()))
        return;
    m_made = true;
    m_forces = forces.size();
    m_radii.assign(radii.begin(), radii.end());
    ++m_generation;
    build(forces);
    findSegments();
    // Only a body with springs can be reached along them: a big ball beside a cloth does not
    // widen every search to the whole cloth.
    double largest = 0.0;
    for (std::size_t i = 0; i < m_radii.size(); ++i)
        if (m_edgeStart[i] < m_edgeStart[i + 1])
            largest = std::max(largest, m_radii[i]);
    const std::size_t n = m_radii.size();
    m_distance.assign(n, kInfinite);
    m_nearStart.assign(n + 1, 0);
    m_near.clear();
    std::vector<std::uint32_t> one;
    for (std::size_t i = 0; i < n; ++i) {
        if (m_radii[i] > 0.0)
            nearOne(i, largest, one);
        m_near.insert(m_near.end(), one.begin(), one.end());
        m_nearStart[i + 1] = m_near.size();
        one.clear();
    }
}

void SpringNeighbours::build(const std::vector<ClonePtr<Force>>& forces)
{
    LinkCollector collector;
    for (const auto& force : forces)
        force->accept(collector);
    // Every spring is an edge: a path through a body without a radius still measures the mesh.
    const std::size_t n = m_radii.size();
    m_edgeStart.assign(n + 1, 0);
    for (const auto& link : collector.links) {
        ++m_edgeStart[link.a + 1];
        ++m_edgeStart[link.b + 1];
    }
    for (std::size_t i = 0; i < n; ++i)
        m_edgeStart[i + 1] += m_edgeStart[i];
    m_edges.resize(m_edgeStart[n]);
    std::vector<std::size_t> fill(m_edgeStart.begin(), m_edgeStart.end() - 1);
    for (const auto& link : collector.links) {
        const double length = std::max(link.restLength, 0.0);
        m_edges[fill[link.a]++] = {std::uint32_t(link.b), length};
        m_edges[fill[link.b]++] = {std::uint32_t(link.a), length};
    }
}

std::span<const SpringNeighbours::Edge> SpringNeighbours::springsOf(std::size_t i) const
{
    return {m_edges.data() + m_edgeStart[i], m_edgeStart[i + 1] - m_edgeStart[i]};
}

double SpringNeighbours::restLength(std::uint32_t i, std::uint32_t j) const
{
    for (const Edge& e : springsOf(i))
        if (e.to == j)
            return e.length;
    return -1.0;
}

void SpringNeighbours::findSegments()
{
    // A spring runs past a third body when going through it is barely longer: a bending
    // spring's two halves add up to it exactly, a shear spring's two sides to 1.41 times it.
    constexpr double kThrough = 1.1;
    m_segments.clear();
    for (std::size_t i = 0; i < m_radii.size(); ++i) {
        if (!(m_radii[i] > 0.0))
            continue;
        for (const Edge& ij : springsOf(i)) {
            if (ij.to <= i || !(m_radii[ij.to] > 0.0))
                continue;
            const bool through = std::any_of(springsOf(i).begin(), springsOf(i).end(), [&](const Edge& ic) {
                const double cj = ic.to == ij.to ? -1.0 : restLength(ic.to, ij.to);
                return cj >= 0.0 && ic.length + cj < kThrough * ij.length;
            });
            if (!through)
                m_segments.emplace_back(std::uint32_t(i), ij.to);
        }
    }
    // Two springs between the same two bodies are one segment.
    std::sort(m_segments.begin(), m_segments.end());
    m_segments.erase(std::unique(m_segments.begin(), m_segments.end()), m_segments.end());
    // Of a cell's two crossing diagonals, only the first (the one the renderer draws the cell's
    // two triangles on): both would rest on a corner under the cell and share it by no rule.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> kept;
    for (const auto& cd : m_segments)
        if (!crossesAnEarlierSegment(cd.first, cd.second))
            kept.push_back(cd);
    m_segments = std::move(kept);
    // The triangles: three bodies each two of which a segment joins (a cloth's cells, halved by
    // the diagonal it is drawn with; a rope has none).
    m_triangles.clear();
    const auto joined = [&](std::uint32_t i, std::uint32_t j) {
        return std::binary_search(m_segments.begin(), m_segments.end(), std::pair(i, j));
    };
    for (const auto& [a, b] : m_segments)
        for (auto ac = std::lower_bound(m_segments.begin(), m_segments.end(), std::pair(a, b + 1));
             ac != m_segments.end() && ac->first == a; ++ac)
            if (joined(b, ac->second))
                m_triangles.push_back({a, b, ac->second});
}

bool SpringNeighbours::crossesAnEarlierSegment(std::uint32_t c, std::uint32_t d) const
{
    // c-d and a-b are a cell's diagonals when each of a and b is joined to both c and d by
    // springs shorter than c-d (the cell's sides).
    const double diagonal = restLength(c, d);
    const auto side = [&](std::uint32_t i, std::uint32_t j) {
        const double l = restLength(i, j);
        return l >= 0.0 && l < diagonal;
    };
    for (const Edge& ca : springsOf(c)) {
        const std::uint32_t a = ca.to;
        if (a == d || !side(c, a) || !side(d, a))
            continue;
        for (const Edge& ab : springsOf(a)) {
            const auto other = std::pair(std::min(a, ab.to), std::max(a, ab.to));
            if (ab.to != c && ab.to != d && side(c, ab.to) && side(d, ab.to) && other < std::pair(c, d) &&
                std::binary_search(m_segments.begin(), m_segments.end(), other))
                return true;
        }
    }
    return false;
}

void SpringNeighbours::nearOne(std::size_t i, double largestRadius, std::vector<std::uint32_t>& out)
{
    if (m_edgeStart[i] == m_edgeStart[i + 1])
        return;
    // Dijkstra's search over the rest lengths, stopped where no body can be a neighbour.
    const double reach = 2.0 * (m_radii[i] + largestRadius);
    using Entry = std::pair<double, std::uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    std::vector<std::uint32_t> seen{std::uint32_t(i)};
    m_distance[i] = 0.0;
    queue.push({0.0, std::uint32_t(i)});
    while (!queue.empty()) {
        const auto [d, at] = queue.top();
        queue.pop();
        if (d > m_distance[at])
            continue;
        for (std::size_t e = m_edgeStart[at]; e < m_edgeStart[at + 1]; ++e) {
            const Edge edge = m_edges[e];
            const double next = d + edge.length;
            const bool joined = at == i; // a spring joins them: neighbours at any length
            if ((next < reach || joined) && next < m_distance[edge.to]) {
                if (m_distance[edge.to] == kInfinite)
                    seen.push_back(edge.to);
                m_distance[edge.to] = next;
                if (next < reach)
                    queue.push({next, edge.to});
            }
        }
    }
    for (const std::uint32_t j : seen) {
        const bool joined = std::any_of(m_edges.begin() + std::ptrdiff_t(m_edgeStart[i]),
                                        m_edges.begin() + std::ptrdiff_t(m_edgeStart[i + 1]),
                                        [&](const Edge& e) { return e.to == j; });
        if (j != i && m_radii[j] > 0.0 && (joined || m_distance[j] < 2.0 * (m_radii[i] + m_radii[j])))
            out.push_back(j);
        m_distance[j] = kInfinite;
    }
    std::sort(out.begin(), out.end());
}

bool SpringNeighbours::near(std::size_t a, std::size_t b) const
{
    if (a + 1 >= m_nearStart.size())
        return false;
    const auto first = m_near.begin() + std::ptrdiff_t(m_nearStart[a]);
    const auto last = m_near.begin() + std::ptrdiff_t(m_nearStart[a + 1]);
    return std::binary_search(first, last, std::uint32_t(b));
}

} // namespace pba::detail
