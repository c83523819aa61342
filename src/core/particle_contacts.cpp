#include "particle_contacts.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "collision_rules.hpp"

namespace pba::detail {

void BallContacts::touch(Ball& a, Ball& b)
{
    const dvec3 d = b.x - a.x;
    const double distance = glm::length(d);
    const double overlap = a.radius + b.radius - distance;
    const double w = a.inverseMass + b.inverseMass;
    if (!(overlap > 0.0) || w == 0.0)
        return;
    const dvec3 n = distance > 0.0 ? d / distance : dvec3(0.0, 1.0, 0.0); // two at one point: one above
    a.x -= (overlap * a.inverseMass / w) * n;
    b.x += (overlap * b.inverseMass / w) * n;
    const dvec3 relative = b.v - a.v;
    const double vn = glm::dot(relative, n);
    if (!(vn < 0.0))
        return;
    // An approach no faster than two steps of their acceleration is resting contact: no rebound
    // (as the room's rules decide it), or a stack would hop.
    const bool resting = -vn <= 2.0 * std::max(a.restingSpeed, b.restingSpeed);
    const double e = resting ? 0.0 : std::sqrt(a.cor * b.cor);
    const double jn = -(1.0 + e) * vn / w; // the normal impulse, N s
    a.v -= (jn * a.inverseMass) * n;
    b.v += (jn * b.inverseMass) * n;
    // Coulomb: the sliding of b over a loses up to mu jn of momentum, and never turns back.
    const double mu = std::sqrt(a.friction * b.friction);
    const dvec3 slide = relative - vn * n;
    const double speed = glm::length(slide);
    if (mu > 0.0 && speed > 0.0) {
        const double jt = std::min(mu * jn, speed / w);
        const dvec3 t = slide / speed;
        a.v += (jt * a.inverseMass) * t;
        b.v -= (jt * b.inverseMass) * t;
    }
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
