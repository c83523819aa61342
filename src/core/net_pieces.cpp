#include "net_pieces.hpp"

#include <algorithm>
#include <cmath>

#include "piece_geometry.hpp"

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
}

bool NetPieces::keep(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments,
                     std::span<const std::array<std::uint32_t, 3>> triangles)
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
    const auto matters = [&](std::uint32_t a, std::uint32_t b) {
        const double length = glm::length(balls[b].x - balls[a].x);
        const double r = std::min(balls[a].radius, balls[b].radius);
        return length - balls[a].radius - balls[b].radius > 0.0 &&
               (4.0 * r - length <= 0.0 || smallest * (4.0 * r - length) < length * (0.5 * length - r));
    };
    for (const auto& [a, b] : segments)
        if (matters(a, b))
            m_kept.push_back({{a, b, b}, 2});
    for (const auto& [a, b, c] : triangles)
        if (matters(a, b) && matters(b, c) && matters(a, c))
            m_kept.push_back({{a, b, c}, 3});
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
                     std::span<const std::array<std::uint32_t, 3>> triangles, std::uint64_t generation,
                     std::vector<BallOnNet>& out)
{
    out.clear();
    if (segments.empty())
        return;
    if (m_netsOf != generation || m_net.size() != balls.size()) {
        findNets(balls, segments);
        m_netsOf = generation;
    }
    if (!m_asking || !keep(balls, segments, triangles))
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

bool NetPieces::touching(std::span<const Ball> balls, const Piece& piece, std::uint32_t ball, BallOnNet& contact)
{
    const Ball& c = balls[ball];
    std::array<dvec3, 3> x{};
    for (int e = 0; e < piece.count; ++e)
        x[std::size_t(e)] = balls[piece.ends[std::size_t(e)]].x;
    const std::span<const dvec3> at(x.data(), std::size_t(piece.count));
    std::array<double, 3> w{};
    if (!footOnPiece(c.x, at, w))
        return false;
    dvec3 point(0.0);
    std::array<double, 3> r{};
    double thickness = 0.0, line = 0.0, inverseMass = 0.0;
    for (int e = 0; e < piece.count; ++e) {
        const Ball& end = balls[piece.ends[std::size_t(e)]];
        const double share = w[std::size_t(e)];
        r[std::size_t(e)] = end.radius;
        point += share * end.x;
        thickness += share * end.radius;
        line += share * (glm::length(c.x - end.x) - end.radius - c.radius);
        inverseMass += share * share * end.inverseMass;
    }
    if (inverseMass + c.inverseMass == 0.0)
        return false;
    const double thickest = thickestPiece(at, std::span<const double>(r.data(), at.size()));
    if (!(thickest > 0.0))
        return false;
    thickness = std::min(thickness, thickest);
    const double separation = glm::length(c.x - point) - thickness - c.radius;
    contact = {piece.ends, w, ball, thickness};
    return separation < 0.0 && separation < line;
}

} // namespace pba::detail
