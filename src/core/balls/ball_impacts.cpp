#include "balls/ball_impacts.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "balls/particle_contacts.hpp"
#include "material_rule.hpp"

namespace pba::detail {

std::optional<double> impactTime(const Ball& a, const Ball& b)
{
    // b - a along the step: d(t) = d0 + t r, t in [0, 1].
    const double reach = a.radius + b.radius;
    const dvec3 d0 = b.start - a.start;
    const dvec3 r = (b.x - b.start) - (a.x - a.start);
    const double rr = glm::dot(r, r), dr = glm::dot(d0, r), c0 = glm::dot(d0, d0) - reach * reach;
    if (!(rr > kImpactMove * kImpactMove * reach * reach) || c0 < 0.0 || dr >= 0.0)
        return std::nullopt; // a short move, touching already (the sweeps' pair), or parting
    const double closest = std::min(1.0, -dr / rr); // the closest approach within the step
    if (glm::dot(d0 + closest * r, d0 + closest * r) >= reach * reach)
        return std::nullopt;
    return (-dr - std::sqrt(std::max(0.0, dr * dr - rr * c0))) / rr;
}

std::optional<bool> meetAt(Ball& a, Ball& b, double t, double dt)
{
    const dvec3 xa = a.start + t * (a.x - a.start), xb = b.start + t * (b.x - b.start);
    const dvec3 n = glm::normalize(xb - xa);
    // The velocities the step ends with, as the sweeps' rule takes them: a path bent by the room
    // within the step (a ball off the floor) is no velocity, and an impulse from it could add
    // energy. Velocities that part the pair already leave it to the sweeps.
    const dvec3 u = b.v - a.v;
    const double un = glm::dot(u, n);
    if (!(un < 0.0))
        return std::nullopt;
    const bool rebounds = -un > 2.0 * std::max(a.restingSpeed, b.restingSpeed);
    const double cor = rebounds ? combinedRestitution(a.cor, b.cor) : 0.0;
    const double normal = -(1.0 + cor) * un;
    dvec3 change = normal * n;
    const dvec3 sliding = u - un * n;
    if (const double length = glm::length(sliding); length > 0.0) {
        const double most = combinedFriction(a.friction, b.friction) * normal;
        change -= (std::min(length, most) / length) * sliding;
    }
    const double w = a.inverseMass + b.inverseMass;
    const dvec3 dva = -(a.inverseMass / w) * change, dvb = (b.inverseMass / w) * change;
    const double rest = (1.0 - t) * dt;
    a.v += dva;
    b.v += dvb;
    a.x += rest * dva;
    b.x += rest * dvb;
    return rebounds;
}

bool BallImpacts::findCandidates(std::span<const Ball> balls)
{
    m_candidates.clear();
    // No ball moved a tenth of its radius: no pair's move reaches a tenth of its reach.
    const bool moved = std::any_of(balls.begin(), balls.end(), [](const Ball& b) {
        const dvec3 move = b.x - b.start;
        return glm::dot(move, move) > kImpactMove * kImpactMove * b.radius * b.radius;
    });
    if (!moved)
        return false;
    // Each path inside a sphere about its middle.
    const auto middle = [&](std::size_t i) { return 0.5 * (balls[i].start + balls[i].x); };
    const auto around = [&](std::size_t i) { return balls[i].radius + 0.5 * glm::length(balls[i].x - balls[i].start); };
    double largest = 0.0;
    for (std::size_t i = 0; i < balls.size(); ++i)
        largest = std::max(largest, around(i));
    m_grid.findPairs(balls.size(), middle, around, largest, m_candidates);
    return !m_candidates.empty();
}

void BallImpacts::meetInOrder(std::span<Ball> balls, std::span<const Plane> planes, double dt)
{
    std::sort(m_impacts.begin(), m_impacts.end(),
              [](const Impact& p, const Impact& q) { return std::tie(p.t, p.a, p.b) < std::tie(q.t, q.a, q.b); });
    m_done.assign(balls.size(), 0);
    for (const Impact& impact : m_impacts) {
        if (m_done[impact.a] || m_done[impact.b])
            continue;
        Ball& a = balls[impact.a];
        Ball& b = balls[impact.b];
        const std::optional<bool> rebounded = meetAt(a, b, impact.t, dt);
        if (!rebounded)
            continue;
        m_done[impact.a] = m_done[impact.b] = 1;
        m_met.push_back({impact.a, impact.b, *rebounded});
        for (Ball* ball : {&a, &b})
            if (ball->inverseMass > 0.0)
                BallContacts::keepInRoom(planes, ~std::uint32_t(0), *ball);
    }
}

} // namespace pba::detail
