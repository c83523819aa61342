#include "particle_contacts.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "collision_rules.hpp"
#include "material_rule.hpp"

namespace pba::detail {

void BallContacts::startContacts(double dt)
{
    m_rules.resize(pairs.size());
    m_contacts.resize(pairs.size());
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        Ball& a = balls[pairs[k].first];
        Ball& b = balls[pairs[k].second];
        m_contacts[k] = newContact(dvec3(b.x - a.x));
        const double w = a.inverseMass + b.inverseMass;
        BallPairRule<double>& rule = m_rules[k];
        rule = {a.radius + b.radius, a.inverseMass / w, b.inverseMass / w, combinedRestitution(a.cor, b.cor),
                combinedFriction(a.friction, b.friction), std::max(a.restingSpeed, b.restingSpeed), dt};
        const std::pair<std::size_t, std::size_t> key(bodies[pairs[k].first], bodies[pairs[k].second]);
        const auto old = std::lower_bound(m_remembered.begin(), m_remembered.end(), key,
                                          [](const auto& entry, const auto& k2) { return entry.first < k2; });
        if (old == m_remembered.end() || old->first != key || a.metInSubsteps || b.metInSubsteps)
            continue;
        const dvec3 d = b.x - a.x;
        const double distance = glm::length(d);
        if (!(distance > 0.0))
            continue;
        const dvec3 n = d / distance;
        BallContact<double>& c = m_contacts[k];
        c = old->second;
        c.tangent -= glm::dot(c.tangent, n) * n;
        const dvec3 change = c.normal * n + c.tangent;
        a.v -= rule.shareA * change;
        b.v += rule.shareB * change;
    }
}

void BallContacts::remember()
{
    m_remembered.clear();
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const Ball& a = balls[pairs[k].first];
        const Ball& b = balls[pairs[k].second];
        m_remembered.emplace_back(std::pair(bodies[pairs[k].first], bodies[pairs[k].second]),
                                  carriedOver(m_contacts[k], dvec3(b.x - a.x), m_rules[k].reach));
    }
    // (The balls are listed in the world's order and the pairs in theirs: the keys are in order.)
    m_rememberedOnSegments.clear();
    for (std::size_t k = 0; k < onSegments.size(); ++k) {
        const BallOnSegment& s = onSegments[k];
        const dvec3 point = (1.0 - s.t) * balls[s.a].x + s.t * balls[s.b].x;
        m_rememberedOnSegments.emplace_back(
            keyOf(s), carriedOver(m_segmentContacts[k], dvec3(balls[s.ball].x - point), m_segmentRules[k].reach));
    }
    std::sort(m_rememberedOnSegments.begin(), m_rememberedOnSegments.end(),
              [](const auto& p, const auto& q) { return p.first < q.first; });
}

void BallContacts::findNets()
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
    // A ball meets the segments of nets other than its own: its own net's far parts meet it by
    // their balls (the self-collision), and asking every ball of a cloth would cost more than
    // its contacts. So with one net, only the balls of none ask.
    m_twoNets = false;
    bool loose = false;
    for (std::uint32_t i = 0; i < balls.size(); ++i) {
        loose = loose || m_net[i] == kNoNet;
        m_twoNets = m_twoNets || (m_net[i] != kNoNet && m_net[i] != m_net[segments[0].first]);
    }
    m_asking = loose || m_twoNets;
    m_netsOf = segmentsGeneration;
}

bool BallContacts::keepSegments()
{
    m_kept.clear();
    if (segments.empty())
        return false;
    if (m_netsOf != segmentsGeneration || m_net.size() != balls.size())
        findNets();
    if (!m_asking)
        return false;
    double smallest = INFINITY;
    for (const Ball& ball : balls)
        smallest = std::min(smallest, ball.radius);
    // A ball of radius rc at the middle of a segment of length L between two balls of radius r,
    // resting on both, lies sqrt((rc + r)^2 - (L/2)^2) from its axis. The segment, as thick as r
    // (or L/2 - r, half its gap, where that is less), holds it further out only when
    // rc (4r - L) < L (L/2 - r): touching balls (a trampoline's) leave no gap for it to matter.
    for (const auto& [a, b] : segments) {
        const double length = glm::length(balls[b].x - balls[a].x);
        const double r = std::min(balls[a].radius, balls[b].radius);
        if (length - balls[a].radius - balls[b].radius > 0.0 &&
            (4.0 * r - length <= 0.0 || smallest * (4.0 * r - length) < length * (0.5 * length - r)))
            m_kept.emplace_back(a, b);
    }
    m_segmentMiddle.resize(m_kept.size());
    m_segmentReach.resize(m_kept.size());
    m_largestSegmentReach = 0.0;
    for (std::size_t s = 0; s < m_kept.size(); ++s) {
        const auto [a, b] = m_kept[s];
        m_segmentMiddle[s] = 0.5 * (balls[a].x + balls[b].x);
        m_segmentReach[s] = 0.5 * glm::length(balls[b].x - balls[a].x) + std::max(balls[a].radius, balls[b].radius);
        m_largestSegmentReach = std::max(m_largestSegmentReach, m_segmentReach[s]);
    }
    return !m_kept.empty();
}

void BallContacts::findOnSegments()
{
    onSegments.clear();
    if (!keepSegments())
        return;
    const auto middle = [&](std::size_t s) { return m_segmentMiddle[s]; };
    const auto reach = [&](std::size_t s) { return m_segmentReach[s]; };
    bool built = false;
    for (std::uint32_t c = 0; c < balls.size(); ++c) {
        if (m_net[c] != kNoNet && !m_twoNets)
            continue;
        if (!built)
            m_segmentGrid.build(m_kept.size(), middle, reach, m_largestSegmentReach);
        built = true;
        m_segmentGrid.near(balls[c].x, balls[c].radius, middle, reach, m_found);
        for (const std::uint32_t s : m_found)
            if (m_net[m_kept[s].first] != m_net[c] && touchingSegment(s, c))
                onSegments.push_back(m_touching);
    }
}

bool BallContacts::touchingSegment(std::uint32_t s, std::uint32_t ball)
{
    const auto [a, b] = m_kept[s];
    const Ball& A = balls[a];
    const Ball& B = balls[b];
    const Ball& C = balls[ball];
    const dvec3 d = B.x - A.x;
    const double length2 = glm::dot(d, d);
    const double gap = std::sqrt(length2) - A.radius - B.radius;
    const double t = glm::dot(C.x - A.x, d) / length2;
    // Nearer an end than this share of the segment, it is that ball's own contact.
    constexpr double kEnd = 0.005;
    if (!(t > kEnd && t < 1.0 - kEnd))
        return false;
    if ((1.0 - t) * (1.0 - t) * A.inverseMass + t * t * B.inverseMass + C.inverseMass == 0.0)
        return false;
    const double radius = std::min(A.radius + t * (B.radius - A.radius), 0.5 * gap);
    const double separation = glm::length(C.x - (A.x + t * d)) - radius - C.radius;
    const double line = (1.0 - t) * (glm::length(C.x - A.x) - A.radius - C.radius) +
                        t * (glm::length(C.x - B.x) - B.radius - C.radius);
    m_touching = {a, b, ball, t, radius};
    return separation < 0.0 && separation < line;
}

void BallContacts::startOnSegments(double dt)
{
    m_segmentRules.resize(onSegments.size());
    m_segmentContacts.resize(onSegments.size());
    for (std::size_t k = 0; k < onSegments.size(); ++k) {
        const BallOnSegment& s = onSegments[k];
        const Ball& A = balls[s.a];
        const Ball& B = balls[s.b];
        Ball& C = balls[s.ball];
        const double ta = 1.0 - s.t, tb = s.t;
        const double w = ta * ta * A.inverseMass + tb * tb * B.inverseMass;
        const double total = w + C.inverseMass;
        const dvec3 d = C.x - (ta * A.x + tb * B.x);
        m_segmentContacts[k] = newContact(d);
        const BallPairRule<double>& rule = m_segmentRules[k] = {
            s.radius + C.radius,
            w / total,
            C.inverseMass / total,
            combinedRestitution(ta * A.cor + tb * B.cor, C.cor),
            combinedFriction(ta * A.friction + tb * B.friction, C.friction),
            std::max({A.restingSpeed, B.restingSpeed, C.restingSpeed}),
            dt};
        const SegmentKey key = keyOf(s);
        const auto old = std::lower_bound(m_rememberedOnSegments.begin(), m_rememberedOnSegments.end(), key,
                                          [](const auto& entry, const SegmentKey& k2) { return entry.first < k2; });
        if (old == m_rememberedOnSegments.end() || old->first != key || A.metInSubsteps || B.metInSubsteps ||
            C.metInSubsteps || !(glm::length(d) > 0.0))
            continue;
        const dvec3 n = glm::normalize(d);
        BallContact<double>& c = m_segmentContacts[k];
        c = old->second;
        c.tangent -= glm::dot(c.tangent, n) * n;
        const dvec3 change = c.normal * n + c.tangent;
        shareOut(s, dvec3(0.0), -rule.shareA * change);
        C.v += rule.shareB * change;
    }
}

void BallContacts::shareOut(const BallOnSegment& s, const dvec3& dx, const dvec3& dv)
{
    Ball& A = balls[s.a];
    Ball& B = balls[s.b];
    const double ta = 1.0 - s.t, tb = s.t;
    const double w = ta * ta * A.inverseMass + tb * tb * B.inverseMass;
    if (!(w > 0.0))
        return;
    // What moved the point by dx moves each end by its share, over the point's inverse mass.
    const dvec3 moved = dx / w, pushed = dv / w;
    A.x += ta * A.inverseMass * moved;
    A.v += ta * A.inverseMass * pushed;
    B.x += tb * B.inverseMass * moved;
    B.v += tb * B.inverseMass * pushed;
}

void BallContacts::touchSegment(const BallOnSegment& s, BallContact<double>& contact, const BallPairRule<double>& rule,
                                bool first)
{
    const Ball& A = balls[s.a];
    const Ball& B = balls[s.b];
    Ball& C = balls[s.ball];
    const double ta = 1.0 - s.t, tb = s.t;
    const dvec3 x0 = ta * A.x + tb * B.x, v0 = ta * A.v + tb * B.v;
    dvec3 x = x0, v = v0;
    touchBalls(x, v, C.x, C.v, contact, rule, first);
    shareOut(s, x - x0, v - v0);
}

void BallContacts::findWalls(std::span<const Plane> planes, double largest)
{
    nearWall.clear();
    for (std::size_t k = 0; k < balls.size(); ++k) {
        const Ball& ball = balls[k];
        const std::uint32_t walls = wallsWithin(planes.first(std::min(planes.size(), kMaxBallPlanes)), ball.x,
                                                ball.radius + 8.0 * largest);
        if (walls != 0 && ball.inverseMass != 0.0)
            nearWall.emplace_back(std::uint32_t(k), walls);
    }
}

void BallContacts::keepInRoom(std::span<const Plane> planes, std::uint32_t walls, Ball& ball)
{
    const std::size_t count = std::min(planes.size(), kMaxBallPlanes);
    for (std::size_t p = 0; p < count; ++p) {
        if (!visits(walls, p))
            continue;
        const Plane plane = planes[p].inflatedBy(ball.radius);
        if (plane.distance(ball.x) < 0.0 && !plane.overHole(ball.x)) {
            collision_detail::snapOnto(plane, ball.x);
            const double vn = glm::dot(plane.normal, ball.v);
            if (vn < 0.0)
                ball.v -= vn * plane.normal;
        }
    }
}

} // namespace pba::detail
