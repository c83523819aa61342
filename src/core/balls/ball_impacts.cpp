#include "balls/ball_impacts.hpp"

#include <algorithm>
#include <array>
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
    if (!a.sprung)
        a.x += rest * dva;
    if (!b.sprung)
        b.x += rest * dvb;
    return rebounds;
}

bool BallImpacts::anyMoved(std::span<const Ball> balls)
{
    // No ball moved a tenth of its radius: no pair's move reaches a tenth of its reach.
    return std::any_of(balls.begin(), balls.end(), [](const Ball& b) {
        const dvec3 move = b.x - b.start;
        return glm::dot(move, move) > kImpactMove * kImpactMove * b.radius * b.radius;
    });
}

void BallImpacts::findCandidates(std::span<const Ball> balls)
{
    // Each path inside a sphere about its middle.
    const auto middle = [&](std::size_t i) { return 0.5 * (balls[i].start + balls[i].x); };
    const auto around = [&](std::size_t i) { return balls[i].radius + 0.5 * glm::length(balls[i].x - balls[i].start); };
    double largest = 0.0;
    for (std::size_t i = 0; i < balls.size(); ++i)
        largest = std::max(largest, around(i));
    m_grid.findPairs(balls.size(), middle, around, largest, m_candidates);
}

void BallImpacts::meetInOrder(std::span<Ball> balls, std::span<const Plane> planes, double dt)
{
    std::sort(m_impacts.begin(), m_impacts.end(), [](const Impact& p, const Impact& q) {
        return std::tie(p.t, p.a, p.b, p.pass) < std::tie(q.t, q.a, q.b, q.pass);
    });
    m_done.assign(balls.size(), 0);
    for (const Impact& impact : m_impacts) {
        // The balls it moves: the two, or the ball and the piece's.
        std::array<std::uint32_t, 4> moves{impact.a, impact.b, impact.b, impact.b};
        if (impact.pass != kNoPass)
            std::copy_n(m_passes[impact.pass].piece.ends.begin(), 3, moves.begin() + 1);
        if (std::any_of(moves.begin(), moves.end(), [&](std::uint32_t k) { return m_done[k] != 0; }))
            continue;
        const std::optional<bool> rebounded =
            impact.pass == kNoPass ? meetAt(balls[impact.a], balls[impact.b], impact.t, dt)
                                   : meetPiece(balls, impact.a, m_passes[impact.pass].piece, impact.t, dt);
        if (!rebounded)
            continue;
        m_met.push_back({impact.a, impact.b, *rebounded});
        for (const std::uint32_t k : moves) {
            m_done[k] = 1;
            if (balls[k].inverseMass > 0.0)
                BallContacts::keepInRoom(planes, ~std::uint32_t(0), balls[k]);
        }
    }
}

std::optional<bool> BallImpacts::meetPiece(std::span<Ball> balls, std::uint32_t k, const NetPoint& piece, double t,
                                           double dt)
{
    Ball point = asBall(balls, piece);
    point.sprung = true;
    const dvec3 before = point.v;
    const std::optional<bool> rebounded = meetAt(balls[k], point, t, dt);
    if (!rebounded || !(point.inverseMass > 0.0))
        return rebounded;
    // What changed the point's velocity by dv changed each ball's by its weight times its
    // inverse mass over the point's (shareOut's rule); its springs move it (Ball::sprung).
    const dvec3 pushed = (point.v - before) / point.inverseMass;
    for (std::size_t e = 0; e < std::size_t(piece.count); ++e) {
        Ball& end = balls[piece.ends[e]];
        end.v += piece.weights[e] * end.inverseMass * pushed;
    }
    return rebounded;
}

} // namespace pba::detail
