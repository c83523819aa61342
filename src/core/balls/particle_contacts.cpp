#include "balls/particle_contacts.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "surfaces/collision_rules.hpp"
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
    m_rememberedOnNets.clear();
    for (std::size_t k = 0; k < onNets.size(); ++k) {
        const NetContact& s = onNets[k];
        const dvec3 d = asBall(balls, s.toucher).x - asBall(balls, s.piece).x;
        m_rememberedOnNets.emplace_back(keyOf(s), carriedOver(m_netContacts[k], d, m_netRules[k].reach));
    }
    std::sort(m_rememberedOnNets.begin(), m_rememberedOnNets.end(),
              [](const auto& p, const auto& q) { return p.first < q.first; });
}

void BallContacts::startOnNets(double dt)
{
    m_netRules.resize(onNets.size());
    m_netContacts.resize(onNets.size());
    for (std::size_t k = 0; k < onNets.size(); ++k) {
        const NetContact& s = onNets[k];
        // Each side as one ball of its point's place, mass and material.
        const Ball piece = asBall(balls, s.piece), toucher = asBall(balls, s.toucher);
        const double total = piece.inverseMass + toucher.inverseMass;
        const dvec3 d = toucher.x - piece.x;
        m_netContacts[k] = newContact(d);
        const BallPairRule<double>& rule = m_netRules[k] = {s.piece.radius + s.toucher.radius,
                                                            piece.inverseMass / total,
                                                            toucher.inverseMass / total,
                                                            combinedRestitution(piece.cor, toucher.cor),
                                                            combinedFriction(piece.friction, toucher.friction),
                                                            std::max(piece.restingSpeed, toucher.restingSpeed),
                                                            dt};
        const bool substeps = piece.metInSubsteps || toucher.metInSubsteps;
        const NetKey key = keyOf(s);
        const auto old = std::lower_bound(m_rememberedOnNets.begin(), m_rememberedOnNets.end(), key,
                                          [](const auto& entry, const NetKey& k2) { return entry.first < k2; });
        if (old == m_rememberedOnNets.end() || old->first != key || substeps || !(glm::length(d) > 0.0))
            continue;
        const dvec3 n = glm::normalize(d);
        BallContact<double>& contact = m_netContacts[k];
        contact = old->second;
        contact.tangent -= glm::dot(contact.tangent, n) * n;
        const dvec3 change = contact.normal * n + contact.tangent;
        shareOut(balls, s.piece, dvec3(0.0), -rule.shareA * change);
        shareOut(balls, s.toucher, dvec3(0.0), rule.shareB * change);
    }
}

void BallContacts::touchNet(const NetContact& s, BallContact<double>& contact, const BallPairRule<double>& rule,
                            bool first)
{
    const Ball piece = asBall(balls, s.piece);
    const dvec3 x0 = piece.x, v0 = piece.v;
    dvec3 x = x0, v = v0;
    if (s.toucher.count == 1) { // a ball: moved where it is
        Ball& c = balls[s.toucher.ends[0]];
        touchBalls(x, v, c.x, c.v, contact, rule, first);
    } else {
        const Ball toucher = asBall(balls, s.toucher);
        const dvec3 y0 = toucher.x, u0 = toucher.v;
        dvec3 y = y0, u = u0;
        touchBalls(x, v, y, u, contact, rule, first);
        shareOut(balls, s.toucher, y - y0, u - u0);
    }
    shareOut(balls, s.piece, x - x0, v - v0);
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
