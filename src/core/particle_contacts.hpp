#pragma once
// Balls against balls: the particles with a radius that touch after a step are pushed apart
// and exchange impulses, with restitution and Coulomb friction, by the rule every ball has
// (ball_rule.hpp), the room standing by as an immovable partner. Private to the core.
//
// Contacts are solved a pair at a time in the grid's order (Gauss-Seidel), a few sweeps a step,
// each pair starting from what it did the step before (its impulses and its static friction's
// anchor, known again by the two bodies); after each sweep every ball is put back inside the
// room (whose push it cannot share). The order is the pairs' index order, so the result does not
// depend on the thread count.
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "ball_rule.hpp"
#include "particle_grid.hpp"
#include "pba/collision.hpp"

namespace pba::detail {

struct Ball {
    dvec3 x{0.0}, v{0.0};
    double inverseMass = 0.0; ///< 0: a fixed ball, which pushes and is not pushed
    double radius = 0.0;
    double cor = 1.0;
    double friction = 0.0;
    double restingSpeed = 0.0; ///< what its acceleration gives in one step, |a| dt
    /// Stepped by XPBD, which keeps it apart from the others inside its substeps: its contacts
    /// here only catch what those left, and start from nothing (a warm start would push apart
    /// what the substeps already hold apart).
    bool metInSubsteps = false;
};

struct BallContacts {
    ParticleGrid grid;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    std::vector<Ball> balls;
    std::vector<std::size_t> bodies; ///< each ball's world index

    std::unique_ptr<BallContacts> clone() const { return std::make_unique<BallContacts>(*this); }

    /// Sweeps over the touching pairs of `balls` (found anew), with `planes` the room's, for a
    /// step of dt. `together(a, b)`: whether balls a and b may touch (a rope's neighbours are
    /// joined instead).
    template <class Together>
    void solve(std::span<const Plane> planes, int sweeps, double dt, Together&& together)
    {
        double largest = 0.0;
        for (const Ball& b : balls)
            largest = std::max(largest, b.radius);
        grid.findPairs(
            balls.size(), [&](std::size_t i) { return balls[i].x; },
            [&](std::size_t i) { return balls[i].radius; }, largest, pairs);
        std::erase_if(pairs, [&](const auto& p) {
            return !together(p.first, p.second) || balls[p.first].inverseMass + balls[p.second].inverseMass == 0.0;
        });
        if (pairs.empty()) {
            m_remembered.clear();
            return;
        }
        findWalls(planes, largest);
        startContacts(dt);
        for (int sweep = 0; sweep < sweeps; ++sweep) {
            for (std::size_t k = 0; k < pairs.size(); ++k) {
                Ball& a = balls[pairs[k].first];
                Ball& b = balls[pairs[k].second];
                touchBalls(a.x, a.v, b.x, b.v, m_contacts[k], m_rules[k], sweep == 0);
            }
            for (const auto& [k, walls] : nearWall)
                keepInRoom(planes, walls, balls[k]);
        }
        remember();
    }

    /// Whether pair k, of the last solve, arrived fast enough to rebound (a bounce, as the room's
    /// and the rigid bodies' contacts count one), rather than rest.
    bool rebounded(std::size_t k) const { return m_contacts[k].bounce > 0.0; }

    /// A ball pushed out of the room by a sweep back on its surfaces (those of `walls`, a bit a
    /// plane), its speed into them taken away.
    static void keepInRoom(std::span<const Plane> planes, std::uint32_t walls, Ball& ball);

private:
    /// Each moving ball within eight of the largest radii of a surface, with those surfaces
    /// (wallsWithin), into nearWall: the sweeps move a ball by its overlaps, each under a diameter.
    void findWalls(std::span<const Plane> planes, double largest);
    /// Each pair's rule, and its contact as the last step left it (warm started: its impulses
    /// given to the balls now).
    void startContacts(double dt);
    /// Each pair's contact for the next step, by its bodies.
    void remember();
    std::vector<std::pair<std::uint32_t, std::uint32_t>> nearWall;
    std::vector<BallPairRule<double>> m_rules;
    std::vector<BallContact<double>> m_contacts;
    /// The last step's contacts, by their bodies' world indices (first < second), in order.
    std::vector<std::pair<std::pair<std::size_t, std::size_t>, BallContact<double>>> m_remembered;
};

} // namespace pba::detail
