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
