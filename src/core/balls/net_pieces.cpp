#include "balls/net_pieces.hpp"

#include <algorithm>
#include <cmath>

#include "balls/ball_impacts.hpp"
#include "balls/piece_geometry.hpp"

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
    // Between two nets any segment with a gap may cross another's, so each such one is kept.
    const auto gapped = [&](std::uint32_t a, std::uint32_t b) {
        return glm::length(balls[b].x - balls[a].x) - balls[a].radius - balls[b].radius > 0.0;
    };
    for (const auto& [a, b] : segments)
        if (m_twoNets ? gapped(a, b) : matters(a, b))
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

bool NetPieces::ready(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments,
                      std::span<const std::array<std::uint32_t, 3>> triangles, std::uint64_t generation)
{
    if (segments.empty())
        return false;
    if (m_netsOf != generation || m_net.size() != balls.size()) {
        findNets(balls, segments);
        m_netsOf = generation;
    }
    if (!m_asking || !keep(balls, segments, triangles))
        return false;
    const auto centre = [&](std::size_t p) { return m_centre[p]; };
    const auto reach = [&](std::size_t p) { return m_reach[p]; };
    m_grid.build(m_kept.size(), centre, reach, m_largestReach);
    return true;
}

void NetPieces::find(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments,
                     std::span<const std::array<std::uint32_t, 3>> triangles, std::uint64_t generation,
                     std::vector<NetContact>& out)
{
    out.clear();
    if (!ready(balls, segments, triangles, generation))
        return;
    const auto centre = [&](std::size_t p) { return m_centre[p]; };
    const auto reach = [&](std::size_t p) { return m_reach[p]; };
    NetContact contact;
    for (std::uint32_t c = 0; c < balls.size(); ++c) {
        if (!asks(c))
            continue;
        m_grid.near(balls[c].x, balls[c].radius, centre, reach, m_found);
        for (const std::uint32_t p : m_found)
            if (m_net[m_kept[p].ends[0]] != m_net[c] && touching(balls, m_kept[p], c, contact))
                out.push_back(contact);
    }
    if (!m_twoNets)
        return;
    // Two nets' segments crossing between their balls, each pair once (p before q).
    for (std::uint32_t p = 0; p < m_kept.size(); ++p) {
        if (m_kept[p].count != 2)
            continue;
        m_grid.near(m_centre[p], m_reach[p], centre, reach, m_found);
        for (const std::uint32_t q : m_found)
            if (q > p && m_kept[q].count == 2 && m_net[m_kept[q].ends[0]] != m_net[m_kept[p].ends[0]] &&
                crossing(balls, m_kept[p], m_kept[q], contact))
                out.push_back(contact);
    }
}

void NetPieces::findPasses(std::span<const Ball> balls,
                           std::span<const std::pair<std::uint32_t, std::uint32_t>> segments,
                           std::span<const std::array<std::uint32_t, 3>> triangles, std::uint64_t generation,
                           std::vector<PiecePass>& out)
{
    out.clear();
    if (!ready(balls, segments, triangles, generation))
        return;
    // A piece a ball met lies within the ball's way and the piece's own (at most the farthest any
    // net's ball went) of where the ball is now.
    double farthest = 0.0;
    for (std::uint32_t b = 0; b < balls.size(); ++b)
        if (m_net[b] != kNoNet)
            farthest = std::max(farthest, glm::length(balls[b].x - balls[b].start));
    const auto centre = [&](std::size_t p) { return m_centre[p]; };
    const auto reach = [&](std::size_t p) { return m_reach[p]; };
    PiecePass pass;
    for (std::uint32_t c = 0; c < balls.size(); ++c) {
        const double way = glm::length(balls[c].x - balls[c].start) + farthest;
        if (!asks(c) || !(way > kImpactMove * balls[c].radius))
            continue; // (no pair's move reaches a tenth of its reach)
        m_grid.near(balls[c].x, balls[c].radius + way, centre, reach, m_found);
        for (const std::uint32_t p : m_found)
            if (m_net[m_kept[p].ends[0]] != m_net[c] && passing(balls, m_kept[p], c, pass))
                out.push_back(pass);
    }
}

bool NetPieces::passing(std::span<const Ball> balls, const Piece& piece, std::uint32_t ball, PiecePass& pass)
{
    const Ball& c = balls[ball];
    const std::size_t count = std::size_t(piece.count);
    std::array<dvec3, 3> at{};
    std::array<double, 3> r{};
    for (std::size_t e = 0; e < count; ++e)
        r[e] = balls[piece.ends[e]].radius;
    const std::span<const dvec3> piecePlaces(at.data(), count);
    // The piece's point the ball came nearest: the weights of the ball's foot on the piece at
    // the time it came nearest the point the last weights named, three times over from the
    // middle of the step (a piece turns and stretches little in a step).
    NetPoint point{piece.ends, {1.0 / double(count), 1.0 / double(count), count == 3 ? 1.0 / 3.0 : 0.0}, piece.count};
    double t = 0.5;
    bool inside = false;
    for (int round = 0; round < 4; ++round) {
        for (std::size_t e = 0; e < count; ++e) {
            const Ball& end = balls[piece.ends[e]];
            at[e] = end.start + t * (end.x - end.start);
        }
        inside = footOnPiece(c.start + t * (c.x - c.start), piecePlaces, point.weights);
        if (round == 3)
            break;
        const Ball p = asBall(balls, point);
        const dvec3 d0 = p.start - c.start, move = (p.x - p.start) - (c.x - c.start);
        const double moved = glm::dot(move, move);
        t = moved > 0.0 ? std::clamp(-glm::dot(d0, move) / moved, 0.0, 1.0) : 0.0;
    }
    const double thickest = thickestPiece(piecePlaces, std::span<const double>(r.data(), count));
    if (!inside || !(thickest > 0.0))
        return false; // beside it (or at a ball: that ball's own impact), or where two balls touch
    point.radius = 0.0;
    for (std::size_t e = 0; e < count; ++e)
        point.radius += point.weights[e] * r[e];
    point.radius = std::min(point.radius, thickest);
    const Ball p = asBall(balls, point);
    if (p.inverseMass + c.inverseMass == 0.0)
        return false;
    const std::optional<double> when = impactTime(c, p);
    if (!when)
        return false;
    pass = {*when, ball, point};
    return true;
}

bool NetPieces::touching(std::span<const Ball> balls, const Piece& piece, std::uint32_t ball, NetContact& contact)
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
    contact = {{piece.ends, w, piece.count, thickness}, NetPoint::ball(ball, c.radius)};
    return separation < 0.0 && separation < line;
}

namespace {

/// The parameters s on p0 + s (p1 - p0) and t on q0 + t (q1 - q0) of the two segments' nearest
/// points, each in [0, 1] (a parallel pair's at s = 0).
std::pair<double, double> nearestOnSegments(const dvec3& p0, const dvec3& p1, const dvec3& q0, const dvec3& q1)
{
    const dvec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
    const double c = glm::dot(d1, r), b = glm::dot(d1, d2);
    const double denominator = a * e - b * b;
    double s = denominator > 1e-12 * a * e ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
    double t = (b * s + f) / e;
    if (t < 0.0)
        t = 0.0, s = std::clamp(-c / a, 0.0, 1.0);
    else if (t > 1.0)
        t = 1.0, s = std::clamp((b - c) / a, 0.0, 1.0);
    return {s, t};
}

/// How far a ball of radius r at c lies from the segment from a to b as thick as `thickness` at
/// each t (its nearest point's).
template <class Thickness>
double ballToSegment(const dvec3& c, double r, const dvec3& a, const dvec3& b, const Thickness& thickness)
{
    const dvec3 d = b - a;
    const double t = std::clamp(glm::dot(c - a, d) / glm::dot(d, d), 0.0, 1.0);
    return glm::length(c - (a + t * d)) - r - thickness(t);
}

} // namespace

bool NetPieces::crossing(std::span<const Ball> balls, const Piece& p, const Piece& q, NetContact& contact)
{
    const Ball &p0 = balls[p.ends[0]], &p1 = balls[p.ends[1]], &q0 = balls[q.ends[0]], &q1 = balls[q.ends[1]];
    if (p0.inverseMass + p1.inverseMass + q0.inverseMass + q1.inverseMass == 0.0)
        return false;
    const auto [s, t] = nearestOnSegments(p0.x, p1.x, q0.x, q1.x);
    if (!(s > kPieceEdge && s < 1.0 - kPieceEdge && t > kPieceEdge && t < 1.0 - kPieceEdge))
        return false; // at a ball: that ball's own contact
    const double thickestP = thickestPiece(std::array{p0.x, p1.x}, std::array{p0.radius, p1.radius});
    const double thickestQ = thickestPiece(std::array{q0.x, q1.x}, std::array{q0.radius, q1.radius});
    if (!(thickestP > 0.0 && thickestQ > 0.0))
        return false;
    const auto thickP = [&](double u) { return std::min((1.0 - u) * p0.radius + u * p1.radius, thickestP); };
    const auto thickQ = [&](double u) { return std::min((1.0 - u) * q0.radius + u * q1.radius, thickestQ); };
    const dvec3 atP = p0.x + s * (p1.x - p0.x), atQ = q0.x + t * (q1.x - q0.x);
    const double separation = glm::length(atQ - atP) - thickP(s) - thickQ(t);
    // Deeper than each segment's balls lie against the other (their own contacts hold those).
    const double lineP = (1.0 - s) * ballToSegment(p0.x, p0.radius, q0.x, q1.x, thickQ) +
                         s * ballToSegment(p1.x, p1.radius, q0.x, q1.x, thickQ);
    const double lineQ = (1.0 - t) * ballToSegment(q0.x, q0.radius, p0.x, p1.x, thickP) +
                         t * ballToSegment(q1.x, q1.radius, p0.x, p1.x, thickP);
    if (!(separation < 0.0 && separation < std::min(lineP, lineQ) - kPieceLevel))
        return false;
    contact = {{p.ends, {1.0 - s, s, 0.0}, 2, thickP(s)}, {q.ends, {1.0 - t, t, 0.0}, 2, thickQ(t)}};
    return true;
}

} // namespace pba::detail
