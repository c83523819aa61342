#include "balls/ball_impacts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include "balls/particle_contacts.hpp"
#include "material_rule.hpp"

namespace pba::detail {

dvec3 placeAt(const Ball& ball, double t)
{
    return ball.since >= t ? ball.start : ball.start + (t - ball.since) / (1.0 - ball.since) * (ball.x - ball.start);
}

std::optional<double> impactTime(const Ball& a, const Ball& b)
{
    // From when both paths run, b - a: d(s) = d0 + s r, s in [0, 1] over the rest of the step.
    const double from = std::max(a.since, b.since);
    if (!(from < 1.0))
        return std::nullopt;
    const double reach = a.radius + b.radius;
    const dvec3 a0 = placeAt(a, from), b0 = placeAt(b, from);
    const dvec3 d0 = b0 - a0;
    const dvec3 r = (b.x - b0) - (a.x - a0);
    const double rr = glm::dot(r, r), dr = glm::dot(d0, r), c0 = glm::dot(d0, d0) - reach * reach;
    if (!(rr > kImpactMove * kImpactMove * reach * reach) || c0 < 0.0 || dr >= 0.0)
        return std::nullopt; // a short move, touching already (the sweeps' pair), or parting
    const double closest = std::min(1.0, -dr / rr); // the closest approach within the step
    if (glm::dot(d0 + closest * r, d0 + closest * r) >= reach * reach)
        return std::nullopt;
    return from + (1.0 - from) * (-dr - std::sqrt(std::max(0.0, dr * dr - rr * c0))) / rr;
}

std::optional<bool> meetAt(Ball& a, Ball& b, double t, double dt)
{
    const dvec3 xa = placeAt(a, t), xb = placeAt(b, t);
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
    // A free ball's path runs on from where it met the other (its impacts later in the step are
    // looked for along it).
    for (auto [ball, at, dv] : {std::tuple(&a, xa, dva), std::tuple(&b, xb, dvb)}) {
        ball->v += dv;
        if (ball->sprung)
            continue;
        ball->x += rest * dv;
        ball->start = at;
        ball->since = t;
    }
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
    m_middle.resize(balls.size());
    m_around.resize(balls.size());
    double largest = 0.0;
    for (std::size_t i = 0; i < balls.size(); ++i) {
        m_middle[i] = 0.5 * (balls[i].start + balls[i].x);
        m_around[i] = balls[i].radius + 0.5 * glm::length(balls[i].x - balls[i].start);
        largest = std::max(largest, m_around[i]);
    }
    m_grid.findPairs(
        balls.size(), [&](std::size_t i) { return m_middle[i]; }, [&](std::size_t i) { return m_around[i]; }, largest,
        m_candidates);
}

void BallImpacts::meetInOrder(std::span<Ball> balls, std::span<const Plane> planes, double dt)
{
    const auto key = [](const Impact& p) { return std::tie(p.t, p.a, p.b, p.pass); };
    std::sort(m_impacts.begin(), m_impacts.end(), [&](const Impact& p, const Impact& q) { return key(p) < key(q); });
    // (A pair found from both of its balls comes twice.)
    m_impacts.erase(std::unique(m_impacts.begin(), m_impacts.end(),
                                [&](const Impact& p, const Impact& q) { return key(p) == key(q); }),
                    m_impacts.end());
    m_done.assign(balls.size(), 0);
    m_moved.clear();
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
        for (const std::uint32_t k : {impact.a, impact.b})
            if (!balls[k].sprung && balls[k].inverseMass > 0.0 &&
                (m_moved.empty() || m_moved.back() != k))
                m_moved.push_back(k);
    }
    std::sort(m_moved.begin(), m_moved.end());
}

std::optional<bool> BallImpacts::meetPiece(std::span<Ball> balls, std::uint32_t k, const NetPoint& piece, double t,
                                           double dt)
{
    Ball point = asBall(balls, piece);
    point.sprung = true;
    const dvec3 before = point.v;
    const std::optional<bool> rebounded = meetAt(balls[k], point, t, dt);
    if (rebounded) // its velocity only: its springs move it (Ball::sprung)
        shareOut(balls, piece, dvec3(0.0), point.v - before);
    return rebounded;
}

} // namespace pba::detail
