#include "study/ball_watch.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "pba/overlap.hpp"
#include "pba/particle.hpp"
#include "pba/rigid_body.hpp"

namespace pba::study {

namespace {

std::size_t rootOf(std::vector<std::size_t>& parent, std::size_t i)
{
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

} // namespace

BallWatch::BallWatch(const World& world, const std::vector<bool>& inFabric,
                     const std::vector<std::pair<std::size_t, std::size_t>>& edges)
{
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        if (world.isRigid(i)) {
            m_bodies.push_back(i);
            continue;
        }
        const auto* p = dynamic_cast<const Particle*>(&world.body(i));
        if (!p || !(p->getRadius() > 0.0))
            continue;
        m_balls.push_back(i);
        m_radii.push_back(p->getRadius());
        m_free.push_back(!p->isFixed() && !(i < inFabric.size() && inFabric[i]));
        m_fixed.push_back(p->isFixed());
    }
    // A ball and a body a joint joins may lie in each other (a crate hung from a rope's end).
    for (std::size_t j = 0; j < world.jointCount(); ++j)
        if (const JointFrame frame = world.jointFrame(j); frame.bodyB) {
            m_joined.emplace_back(frame.bodyA, *frame.bodyB);
            m_joined.emplace_back(*frame.bodyB, frame.bodyA);
        }
    std::sort(m_joined.begin(), m_joined.end());
    for (const auto& [a, b] : edges) {
        const auto ia = std::lower_bound(m_balls.begin(), m_balls.end(), a);
        const auto ib = std::lower_bound(m_balls.begin(), m_balls.end(), b);
        if (ia != m_balls.end() && *ia == a && ib != m_balls.end() && *ib == b)
            m_segments.emplace_back(std::size_t(ia - m_balls.begin()), std::size_t(ib - m_balls.begin()));
    }
    m_figures.segments = m_segments.size();
    // The cloths' triangles: three balls each two of which an edge joins.
    std::vector<std::vector<std::size_t>> joined(m_balls.size());
    for (const auto& [i, j] : m_segments) {
        joined[i].push_back(j);
        joined[j].push_back(i);
    }
    for (auto& list : joined)
        std::sort(list.begin(), list.end());
    for (const auto& [i, j] : m_segments)
        for (const std::size_t k : joined[i])
            if (k > std::max(i, j) && std::binary_search(joined[j].begin(), joined[j].end(), k))
                m_triangles.push_back({i, j, k});
    // Each ball's net: the balls its edges reach.
    std::vector<std::size_t> parent(m_balls.size());
    std::iota(parent.begin(), parent.end(), std::size_t(0));
    for (const auto& [i, j] : m_segments)
        parent[rootOf(parent, i)] = rootOf(parent, j);
    m_netOf.assign(m_balls.size(), kNoNet);
    for (const auto& [i, j] : m_segments)
        m_netOf[i] = m_netOf[j] = rootOf(parent, i);
    for (std::size_t k = 0; k < m_balls.size(); ++k)
        m_figures.nets += std::size_t(m_netOf[k] == k);
    m_figures.balls = m_balls.size();
    m_figures.freeBalls = std::size_t(std::count(m_free.begin(), m_free.end(), true));
    // The start: the balls in the bodies now; which pairs collide (a cloth's neighbours along its
    // springs do not) is the first step's knowledge, so those are looked at after it.
    m_startCentres = centresOf(world);
    m_startTime = world.time();
    lookIntoBodies(world, m_startCentres, m_startTime);
}

std::vector<dvec3> BallWatch::centresOf(const World& world) const
{
    std::vector<dvec3> centres(m_balls.size());
    for (std::size_t k = 0; k < m_balls.size(); ++k)
        centres[k] = world.body(m_balls[k]).getPos();
    return centres;
}

void BallWatch::record(const World& world)
{
    if (!active())
        return;
    if (m_steps == 0)
        lookAtPairs(world, m_startCentres, m_startTime);
    if (++m_steps % kEvery == 0)
        look(world);
}

void BallWatch::finish(const World& world)
{
    if (active() && m_steps % kEvery != 0)
        look(world);
}

void BallWatch::look(const World& world)
{
    const std::vector<dvec3> centres = centresOf(world);
    lookAtPairs(world, centres, world.time());
    lookIntoBodies(world, centres, world.time());
    lookBetweenBalls(world, centres, world.time());
    lookIntoEdges(centres, world.time());
}

void BallWatch::lookAtPairs(const World& world, const std::vector<dvec3>& centres, double now)
{
    std::vector<std::size_t> group(m_balls.size());
    std::iota(group.begin(), group.end(), std::size_t(0));
    for (const auto& [i, j] : nearBallPairs(centres, m_radii, kTouch)) {
        const double gap = glm::length(centres[j] - centres[i]) - m_radii[i] - m_radii[j];
        if (m_free[i] && m_free[j] && gap < std::min(kTouch, kTouchShare * (m_radii[i] + m_radii[j])))
            group[rootOf(group, i)] = rootOf(group, j); // touching
        if (gap >= 0.0 || !world.ballsCollide(m_balls[i], m_balls[j]) || (m_fixed[i] && m_fixed[j]))
            continue; // (two fixed balls do not meet: neither moves)
        const double share = -gap / (2.0 * std::min(m_radii[i], m_radii[j]));
        if (share > m_figures.deepestPair)
            m_figures.deepestPair = share, m_figures.deepestPairAt = now;
    }
    if (m_figures.freeBalls < 2)
        return;
    std::optional<std::size_t> root;
    bool one = true;
    for (std::size_t k = 0; k < m_balls.size(); ++k)
        if (m_free[k]) {
            const std::size_t r = rootOf(group, k);
            one = one && (!root || *root == r);
            root = r;
        }
    if (!one)
        m_figures.oneGroupFrom.reset();
    else if (!m_figures.oneGroupFrom)
        m_figures.oneGroupFrom = now;
}

void BallWatch::lookIntoBodies(const World& world, const std::vector<dvec3>& centres, double now)
{
    // The balls by x, so that a body looks only at those within its reach along x (a cloth of
    // thousands of balls beside a heap of dice was every ball against every die).
    std::vector<std::pair<double, std::size_t>> byX(m_balls.size());
    for (std::size_t k = 0; k < m_balls.size(); ++k)
        byX[k] = {centres[k].x, k};
    std::sort(byX.begin(), byX.end());
    const double largest = m_radii.empty() ? 0.0 : *std::max_element(m_radii.begin(), m_radii.end());
    for (const std::size_t b : m_bodies) {
        const auto& body = static_cast<const RigidBody&>(world.body(b));
        const double reach = body.getBoundingRadius() + largest;
        const auto first = std::lower_bound(byX.begin(), byX.end(), std::pair(body.getPos().x - reach, std::size_t(0)));
        for (auto it = first; it != byX.end() && it->first <= body.getPos().x + reach; ++it) {
            const std::size_t k = it->second;
            if (glm::length(centres[k] - body.getPos()) >= body.getBoundingRadius() + m_radii[k] ||
                std::binary_search(m_joined.begin(), m_joined.end(), std::pair(m_balls[k], b)))
                continue;
            const double depth = overlapDepth(body, centres[k], m_radii[k]);
            if (depth > m_figures.deepestInBody)
                m_figures.deepestInBody = depth, m_figures.deepestInBodyAt = now,
                m_figures.deepestBody = body.getName();
        }
    }
}

void BallWatch::lookBetweenBalls(const World& world, const std::vector<dvec3>& centres, double now)
{
    constexpr int kPieces = 16;
    for (const std::size_t b : m_bodies) {
        const auto& body = static_cast<const RigidBody&>(world.body(b));
        const auto joined = [&](std::size_t k) {
            return std::binary_search(m_joined.begin(), m_joined.end(), std::pair(m_balls[k], b));
        };
        for (const auto& [i, j] : m_segments) {
            if (joined(i) || joined(j))
                continue;
            const double depth = overlapDepth(body, centres[i], m_radii[i], centres[j], m_radii[j], kPieces);
            if (depth > m_figures.deepestBetween)
                m_figures.deepestBetween = depth, m_figures.deepestBetweenAt = now,
                m_figures.deepestBetweenBody = body.getName();
        }
        for (const auto& t : m_triangles) {
            if (joined(t[0]) || joined(t[1]) || joined(t[2]))
                continue;
            const double depth = overlapDepth(body, {centres[t[0]], centres[t[1]], centres[t[2]]},
                                              {m_radii[t[0]], m_radii[t[1]], m_radii[t[2]]});
            if (depth > m_figures.deepestBetween)
                m_figures.deepestBetween = depth, m_figures.deepestBetweenAt = now,
                m_figures.deepestBetweenBody = body.getName();
        }
    }
}

namespace {

/// How far a ball of radius r at c goes into the edge from a (radius ra) to b (rb), as thick as
/// its balls but no thicker than half the gap between them, at the edge's inner point nearest c
/// (at its ends it is the balls' own overlap).
double intoEdge(const dvec3& c, double r, const dvec3& a, double ra, const dvec3& b, double rb)
{
    const dvec3 d = b - a;
    const double length = glm::length(d);
    const double gap = length - ra - rb;
    if (!(gap > 0.0))
        return 0.0;
    const double t = glm::dot(c - a, d) / (length * length);
    if (!(t > 0.0 && t < 1.0))
        return 0.0;
    const double thickness = std::min(ra + t * (rb - ra), 0.5 * gap);
    return r + thickness - glm::length(c - (a + t * d));
}

/// How far a ball of radius r at c goes into the triangle x (radii rs), as thick as its balls by
/// where c's foot lies on it but no thicker than half the gap between two of them, where that
/// foot lies inside it (at its sides and corners it is the edges' and the balls' own overlap).
double intoTriangle(const dvec3& c, double r, const std::array<dvec3, 3>& x, const std::array<double, 3>& rs)
{
    const dvec3 e1 = x[1] - x[0], e2 = x[2] - x[0], q = c - x[0];
    const dvec3 normal = glm::cross(e1, e2);
    const double twiceArea = glm::length(normal);
    if (!(twiceArea > 0.0))
        return 0.0;
    // The foot's barycentric weights, by the areas of the triangles it makes with each side.
    const dvec3 n = normal / twiceArea;
    const double u = glm::dot(glm::cross(q, e2), n) / twiceArea, v = glm::dot(glm::cross(e1, q), n) / twiceArea;
    const std::array<double, 3> w{1.0 - u - v, u, v};
    if (!(w[0] > 0.0 && w[1] > 0.0 && w[2] > 0.0))
        return 0.0;
    const double thickest = halfSmallestGap(x, rs);
    if (!(thickest > 0.0))
        return 0.0;
    const double thickness = std::min(w[0] * rs[0] + w[1] * rs[1] + w[2] * rs[2], thickest);
    return r + thickness - std::abs(glm::dot(q, n));
}

} // namespace

void BallWatch::lookIntoEdges(const std::vector<dvec3>& centres, double now)
{
    // The balls that meet other nets' edges: free balls, and the nets' own when there are two.
    std::vector<std::size_t> asking;
    for (std::size_t k = 0; k < m_balls.size(); ++k)
        if (m_free[k] || (m_figures.nets >= 2 && m_netOf[k] != kNoNet))
            asking.push_back(k);
    if (asking.empty() || m_segments.empty())
        return;
    // Each piece (an edge, then a triangle) by the sphere around it, for the grid.
    std::vector<std::array<std::size_t, 3>> pieces;
    for (const auto& [i, j] : m_segments)
        pieces.push_back({i, j, j});
    pieces.insert(pieces.end(), m_triangles.begin(), m_triangles.end());
    std::vector<dvec3> around(pieces.size());
    std::vector<double> reach(pieces.size());
    for (std::size_t p = 0; p < pieces.size(); ++p) {
        const auto& e = pieces[p];
        around[p] = (centres[e[0]] + centres[e[1]] + centres[e[2]]) / 3.0;
        for (const std::size_t b : e)
            reach[p] = std::max(reach[p], glm::length(centres[b] - around[p]) + m_radii[b]);
    }
    std::vector<dvec3> askingAt(asking.size());
    std::vector<double> askingRadii(asking.size());
    for (std::size_t a = 0; a < asking.size(); ++a)
        askingAt[a] = centres[asking[a]], askingRadii[a] = m_radii[asking[a]];
    for (const auto& [a, p] : ballsInSpheres(askingAt, askingRadii, around, reach)) {
        const std::size_t k = asking[a];
        const auto& e = pieces[p];
        if (!m_free[k] && m_netOf[k] == m_netOf[e[0]])
            continue; // its own net's: its far balls meet it by their balls alone
        if (m_fixed[k] && m_fixed[e[0]] && m_fixed[e[1]] && m_fixed[e[2]])
            continue; // (nothing fixed moves: they do not meet)
        const double depth =
            p < m_segments.size()
                ? intoEdge(centres[k], m_radii[k], centres[e[0]], m_radii[e[0]], centres[e[1]], m_radii[e[1]])
                : intoTriangle(centres[k], m_radii[k], {centres[e[0]], centres[e[1]], centres[e[2]]},
                               {m_radii[e[0]], m_radii[e[1]], m_radii[e[2]]});
        double& deepest = m_free[k] ? m_figures.deepestFreeInEdge : m_figures.deepestNetBallInEdge;
        double& at = m_free[k] ? m_figures.deepestFreeInEdgeAt : m_figures.deepestNetBallInEdgeAt;
        if (depth > deepest)
            deepest = depth, at = now;
    }
    if (m_figures.nets >= 2)
        lookAtCrossings(centres, around, reach, now);
}

void BallWatch::lookAtCrossings(const std::vector<dvec3>& centres, const std::vector<dvec3>& around,
                                const std::vector<double>& reach, double now)
{
    // Two nets' edges (the first pieces), each looked at in 16 pieces along it against the other.
    constexpr int kPieces = 16;
    const std::size_t edges = m_segments.size();
    const std::span<const dvec3> edgesAround(around.data(), edges);
    const std::span<const double> edgesReach(reach.data(), edges);
    for (const auto& [p, q] : ballsInSpheres(edgesAround, edgesReach, edgesAround, edgesReach)) {
        const auto [a, b] = m_segments[p];
        const auto [c, d] = m_segments[q];
        if (q <= p || m_netOf[a] == m_netOf[c] || (m_fixed[a] && m_fixed[b] && m_fixed[c] && m_fixed[d]))
            continue;
        // Each edge's pieces against the other edge, both ways.
        const auto look = [&](std::size_t i, std::size_t j, std::size_t k, std::size_t l) {
            const double gap = glm::length(centres[j] - centres[i]) - m_radii[i] - m_radii[j];
            if (!(gap > 0.0))
                return;
            for (int n = 1; n < kPieces; ++n) {
                const double u = double(n) / kPieces;
                const double thickness = std::min(m_radii[i] + u * (m_radii[j] - m_radii[i]), 0.5 * gap);
                const double depth = intoEdge(centres[i] + u * (centres[j] - centres[i]), thickness, centres[k],
                                              m_radii[k], centres[l], m_radii[l]);
                if (depth > m_figures.deepestNetBallInEdge)
                    m_figures.deepestNetBallInEdge = depth, m_figures.deepestNetBallInEdgeAt = now;
            }
        };
        look(a, b, c, d);
        look(c, d, a, b);
    }
}

} // namespace pba::study
