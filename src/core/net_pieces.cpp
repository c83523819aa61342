#include "net_pieces.hpp"

#include <algorithm>
#include <cmath>

namespace pba::detail {

void NetPieces::findNets(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments)
{
    // The balls that segments join, by union-find (a net's first ball its root).
    m_net.resize(balls.size());
    for (std::size_t i = 0; i < balls.size(); ++i)
        m_net[i] = std::uint32_t(i);
    const auto root = [&](std::uint32_t i) {
        while (m_net[i] != i)
            i = m_net[i] = m_net[m_net[i]];
        return i;
    };
    for (const auto& [a, b] : segments) {
        const std::uint32_t ra = root(a), rb = root(b);
        m_net[std::max(ra, rb)] = std::min(ra, rb);
    }
    std::vector<std::uint8_t> inNet(balls.size(), 0);
    for (const auto& [a, b] : segments)
        inNet[a] = inNet[b] = 1;
    for (std::uint32_t i = 0; i < balls.size(); ++i)
        m_net[i] = inNet[i] ? root(i) : kNoNet;
    m_twoNets = false;
    bool loose = false;
    for (std::uint32_t i = 0; i < balls.size(); ++i) {
        loose = loose || m_net[i] == kNoNet;
        m_twoNets = m_twoNets || (m_net[i] != kNoNet && m_net[i] != m_net[segments[0].first]);
    }
    m_asking = loose || m_twoNets;
    // The triangles: three balls each two of which a segment joins (a cloth's cells, halved by
    // the diagonal it is drawn with; a rope has none).
    std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> joined(balls.size()); // (ball, segment)
    for (std::uint32_t s = 0; s < segments.size(); ++s) {
        joined[segments[s].first].emplace_back(segments[s].second, s);
        joined[segments[s].second].emplace_back(segments[s].first, s);
    }
    for (auto& list : joined)
        std::sort(list.begin(), list.end());
    const auto segmentBetween = [&](std::uint32_t i, std::uint32_t j) -> std::int64_t {
        const auto it = std::lower_bound(joined[i].begin(), joined[i].end(), std::pair(j, std::uint32_t(0)));
        return it != joined[i].end() && it->first == j ? std::int64_t(it->second) : -1;
    };
    m_triangles.clear();
    for (std::uint32_t s = 0; s < segments.size(); ++s) {
        const std::uint32_t a = std::min(segments[s].first, segments[s].second);
        const std::uint32_t b = std::max(segments[s].first, segments[s].second);
        for (const auto& [c, ac] : joined[a])
            if (c > b)
                if (const std::int64_t bc = segmentBetween(b, c); bc >= 0)
                    m_triangles.push_back({{a, b, c}, 3, {s, ac, std::uint32_t(bc)}});
    }
}

bool NetPieces::keep(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments)
{
    m_kept.clear();
    double smallest = INFINITY;
    for (const Ball& ball : balls)
        smallest = std::min(smallest, ball.radius);
    // A ball of radius rc at the middle of a segment of length L between two balls of radius r,
    // resting on both, lies sqrt((rc + r)^2 - (L/2)^2) from its axis. The segment, as thick as r
    // (or L/2 - r, half its gap, where that is less), holds it further out only when
    // rc (4r - L) < L (L/2 - r): touching balls (a trampoline's) leave no gap for it to matter.
    // A triangle counts where its three sides do.
    m_keptSegment.assign(segments.size(), 0);
    for (std::size_t s = 0; s < segments.size(); ++s) {
        const auto [a, b] = segments[s];
        const double length = glm::length(balls[b].x - balls[a].x);
        const double r = std::min(balls[a].radius, balls[b].radius);
        if (length - balls[a].radius - balls[b].radius > 0.0 &&
            (4.0 * r - length <= 0.0 || smallest * (4.0 * r - length) < length * (0.5 * length - r))) {
            m_keptSegment[s] = 1;
            m_kept.push_back({{a, b, b}, 2, {}});
        }
    }
    for (const Piece& t : m_triangles)
        if (m_keptSegment[t.sides[0]] && m_keptSegment[t.sides[1]] && m_keptSegment[t.sides[2]])
            m_kept.push_back(t);
    m_centre.resize(m_kept.size());
    m_reach.resize(m_kept.size());
    m_largestReach = 0.0;
    for (std::size_t p = 0; p < m_kept.size(); ++p) {
        const Piece& piece = m_kept[p];
        dvec3 centre(0.0);
        for (int e = 0; e < piece.count; ++e)
            centre += balls[piece.ends[std::size_t(e)]].x;
        centre /= double(piece.count);
        double reach = 0.0;
        for (int e = 0; e < piece.count; ++e) {
            const Ball& end = balls[piece.ends[std::size_t(e)]];
            reach = std::max(reach, glm::length(end.x - centre) + end.radius);
        }
        m_centre[p] = centre;
        m_reach[p] = reach;
        m_largestReach = std::max(m_largestReach, reach);
    }
    return !m_kept.empty();
}

void NetPieces::find(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments,
                     std::uint64_t generation, std::vector<BallOnNet>& out)
{
    out.clear();
    if (segments.empty())
        return;
    if (m_netsOf != generation || m_net.size() != balls.size()) {
        findNets(balls, segments);
        m_netsOf = generation;
    }
    if (!m_asking || !keep(balls, segments))
        return;
    const auto centre = [&](std::size_t p) { return m_centre[p]; };
    const auto reach = [&](std::size_t p) { return m_reach[p]; };
    m_grid.build(m_kept.size(), centre, reach, m_largestReach);
    BallOnNet contact;
    for (std::uint32_t c = 0; c < balls.size(); ++c) {
        if (m_net[c] != kNoNet && !m_twoNets)
            continue;
        m_grid.near(balls[c].x, balls[c].radius, centre, reach, m_found);
        for (const std::uint32_t p : m_found)
            if (m_net[m_kept[p].ends[0]] != m_net[c] && touching(balls, m_kept[p], c, contact))
                out.push_back(contact);
    }
}

namespace {

/// The point's weights on a segment from a to b nearest p, and on a triangle a, b, c where p's
/// foot on its plane lies (barycentric); false where that point is within `edge` of a side's or
/// an end's share.
bool weightsOf(const dvec3& p, std::span<const dvec3> x, int count, std::array<double, 3>& w)
{
    // Nearer a side or an end than this share, it is that side's or that ball's own contact.
    constexpr double kEdge = 0.005;
    if (count == 2) {
        const dvec3 d = x[1] - x[0];
        const double t = glm::dot(p - x[0], d) / glm::dot(d, d);
        w = {1.0 - t, t, 0.0};
    } else {
        const dvec3 e1 = x[1] - x[0], e2 = x[2] - x[0], q = p - x[0];
        const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
        const double det = d11 * d22 - d12 * d12;
        if (!(det > 0.0))
            return false;
        const double u = (d22 * glm::dot(q, e1) - d12 * glm::dot(q, e2)) / det;
        const double v = (d11 * glm::dot(q, e2) - d12 * glm::dot(q, e1)) / det;
        w = {1.0 - u - v, u, v};
    }
    for (int e = 0; e < count; ++e)
        if (!(w[std::size_t(e)] > kEdge))
            return false;
    return true;
}

} // namespace

bool NetPieces::touching(std::span<const Ball> balls, const Piece& piece, std::uint32_t ball, BallOnNet& contact)
{
    const Ball& c = balls[ball];
    std::array<dvec3, 3> x{};
    for (int e = 0; e < piece.count; ++e)
        x[std::size_t(e)] = balls[piece.ends[std::size_t(e)]].x;
    std::array<double, 3> w{};
    if (!weightsOf(c.x, std::span<const dvec3>(x.data(), std::size_t(piece.count)), piece.count, w))
        return false;
    dvec3 point(0.0);
    double thickness = 0.0, line = 0.0, inverseMass = 0.0;
    for (int e = 0; e < piece.count; ++e) {
        const Ball& end = balls[piece.ends[std::size_t(e)]];
        const double share = w[std::size_t(e)];
        point += share * end.x;
        thickness += share * end.radius;
        line += share * (glm::length(c.x - end.x) - end.radius - c.radius);
        inverseMass += share * share * end.inverseMass;
    }
    if (inverseMass + c.inverseMass == 0.0)
        return false;
    // No thicker than half the gap between any two of its balls.
    for (int e = 0; e < piece.count; ++e) {
        const Ball& a = balls[piece.ends[std::size_t(e)]];
        const Ball& b = balls[piece.ends[std::size_t((e + 1) % piece.count)]];
        const double gap = glm::length(b.x - a.x) - a.radius - b.radius;
        if (!(gap > 0.0))
            return false;
        thickness = std::min(thickness, 0.5 * gap);
    }
    const double separation = glm::length(c.x - point) - thickness - c.radius;
    contact = {piece.ends, w, ball, thickness};
    return separation < 0.0 && separation < line;
}

} // namespace pba::detail
