#include "study/ball_watch.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "pba/overlap.hpp"
#include "pba/particle.hpp"
#include "pba/rigid_body.hpp"

namespace pba::study {

BallWatch::BallWatch(const World& world, const std::vector<bool>& inFabric)
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
    }
    m_figures.balls = m_balls.size();
    m_figures.freeBalls = std::size_t(std::count(m_free.begin(), m_free.end(), true));
}

void BallWatch::record(const World& world)
{
    if (active() && ++m_steps % kEvery == 0)
        look(world);
}

void BallWatch::finish(const World& world)
{
    if (active() && m_steps % kEvery != 0)
        look(world);
}

namespace {

/// The pairs of `centres` (radii `radii`) within `reach` of touching, each once (i < j): a grid
/// of cells as wide as the largest ball and the reach, its cells sorted by their keys.
template <class Visit>
void forNearPairs(const std::vector<dvec3>& centres, const std::vector<double>& radii, double reach, Visit&& visit)
{
    const double cell = 2.0 * *std::max_element(radii.begin(), radii.end()) + reach;
    const auto key = [&](const dvec3& x, int dx, int dy, int dz) {
        const auto c = [&](double v, int d) { return std::uint64_t(std::int64_t(std::floor(v / cell)) + d + (1 << 20)); };
        return (c(x.x, dx) << 42) | (c(x.y, dy) << 21) | c(x.z, dz);
    };
    std::vector<std::pair<std::uint64_t, std::size_t>> cells(centres.size());
    for (std::size_t i = 0; i < centres.size(); ++i)
        cells[i] = {key(centres[i], 0, 0, 0), i};
    std::sort(cells.begin(), cells.end());
    for (std::size_t i = 0; i < centres.size(); ++i)
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const std::uint64_t k = key(centres[i], dx, dy, dz);
                    auto it = std::lower_bound(cells.begin(), cells.end(), std::pair(k, std::size_t(0)));
                    for (; it != cells.end() && it->first == k; ++it)
                        if (const std::size_t j = it->second;
                            j > i && glm::length(centres[j] - centres[i]) < radii[i] + radii[j] + reach)
                            visit(i, j);
                }
}

std::size_t rootOf(std::vector<std::size_t>& parent, std::size_t i)
{
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

} // namespace

void BallWatch::look(const World& world)
{
    const double now = world.time();
    std::vector<dvec3> centres(m_balls.size());
    for (std::size_t k = 0; k < m_balls.size(); ++k)
        centres[k] = world.body(m_balls[k]).getPos();
    std::vector<std::size_t> group(m_balls.size());
    std::iota(group.begin(), group.end(), std::size_t(0));
    forNearPairs(centres, m_radii, kTouch, [&](std::size_t i, std::size_t j) {
        const double gap = glm::length(centres[j] - centres[i]) - m_radii[i] - m_radii[j];
        if (m_free[i] && m_free[j])
            group[rootOf(group, i)] = rootOf(group, j); // within kTouch: touching
        if (gap >= 0.0 || !world.ballsCollide(m_balls[i], m_balls[j]))
            return;
        const double share = -gap / (2.0 * std::min(m_radii[i], m_radii[j]));
        if (share > m_figures.deepestPair)
            m_figures.deepestPair = share, m_figures.deepestPairAt = now;
    });
    for (const std::size_t b : m_bodies) {
        const auto& body = static_cast<const RigidBody&>(world.body(b));
        for (std::size_t k = 0; k < m_balls.size(); ++k) {
            if (glm::length(centres[k] - body.getPos()) >= body.getBoundingRadius() + m_radii[k])
                continue;
            const double depth = overlapDepth(body, centres[k], m_radii[k]);
            if (depth > m_figures.deepestInBody)
                m_figures.deepestInBody = depth, m_figures.deepestInBodyAt = now, m_figures.deepestBody = body.getName();
        }
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

} // namespace pba::study
