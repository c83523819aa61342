#pragma once
// Balls against balls: the particles with a radius that touch after a step are pushed apart
// and exchange impulses, with restitution and Coulomb friction, by the rule every ball has
// (ball_rule.hpp), the room standing by as an immovable partner. Private to the core.
//
// Pairs that met within the step, closing by over a tenth of their reach, are met first, at
// their time of impact (ball_impacts.hpp). Contacts are solved a pair at a time in the grid's
// order (Gauss-Seidel), a few sweeps a step, each pair starting from what it did the step before
// (its impulses and its static friction's anchor, known again by the two bodies); after each
// sweep every ball is put back inside the room (whose push it cannot share). The order is the
// pairs' index order, so the result does not depend on the thread count.
//
// A ball meets the pieces of the ropes and cloths it is not part of too, between their balls,
// and two nets' segments meet where they cross between theirs (net_pieces.hpp), in the same
// sweeps, as balls of their points' masses whose pushes and impulses go to the pieces' balls by
// their weights there.
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "balls/ball.hpp"
#include "balls/ball_impacts.hpp"
#include "balls/ball_rule.hpp"
#include "balls/net_pieces.hpp"
#include "balls/particle_grid.hpp"
#include "pba/collision.hpp"

namespace pba::detail {

struct BallContacts {
    ParticleGrid grid;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    std::vector<Ball> balls;
    std::vector<std::size_t> bodies; ///< each ball's world index
    std::vector<std::uint8_t> sprung; ///< for each body of the world, whether springs join it to another (Ball::sprung)
    /// The nets' segments, as pairs of balls (indices into `balls`); set before solve, with the
    /// generation of the lists they come from (the nets are worked out again when it changes).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> segments;
    std::vector<std::array<std::uint32_t, 3>> triangles; ///< the same, of three balls
    std::uint64_t piecesGeneration = 0;
    /// The balls and segments against pieces of nets of the last solve.
    std::vector<NetContact> onNets;
    /// The pairs that met within the last step, before its sweeps.
    BallImpacts impacts;

    std::unique_ptr<BallContacts> clone() const { return std::make_unique<BallContacts>(*this); }

    /// Sweeps over the touching pairs of `balls` (found anew), with `planes` the room's, for a
    /// step of dt. `together(a, b)`: whether balls a and b may touch (a rope's neighbours are
    /// joined instead).
    template <class Together>
    void solve(std::span<const Plane> planes, int sweeps, double dt, Together&& together)
    {
        impacts.meet(balls, planes, dt, together, [&](std::vector<PiecePass>& passes) {
            m_pieces.findPasses(balls, segments, triangles, piecesGeneration, passes);
        });
        double largest = 0.0;
        for (const Ball& b : balls)
            largest = std::max(largest, b.radius);
        grid.findPairs(
            balls.size(), [&](std::size_t i) { return balls[i].x; },
            [&](std::size_t i) { return balls[i].radius; }, largest, pairs);
        std::erase_if(pairs, [&](const auto& p) {
            return !together(p.first, p.second) || balls[p.first].inverseMass + balls[p.second].inverseMass == 0.0;
        });
        m_pieces.find(balls, segments, triangles, piecesGeneration, onNets);
        if (pairs.empty() && onNets.empty()) {
            m_remembered.clear();
            m_rememberedOnNets.clear();
            return;
        }
        findWalls(planes, largest);
        startContacts(dt);
        startOnNets(dt);
        for (int sweep = 0; sweep < sweeps; ++sweep) {
            for (std::size_t k = 0; k < pairs.size(); ++k) {
                Ball& a = balls[pairs[k].first];
                Ball& b = balls[pairs[k].second];
                touchBalls(a.x, a.v, b.x, b.v, m_contacts[k], m_rules[k], sweep == 0);
            }
            for (std::size_t k = 0; k < onNets.size(); ++k)
                touchNet(onNets[k], m_netContacts[k], m_netRules[k], sweep == 0);
            for (const auto& [k, walls] : nearWall)
                keepInRoom(planes, walls, balls[k]);
        }
        remember();
    }

    /// Whether pair k, of the last solve, arrived fast enough to rebound (a bounce, as the room's
    /// and the rigid bodies' contacts count one), rather than rest.
    bool rebounded(std::size_t k) const { return m_contacts[k].bounce > 0.0; }
    /// The same for onNets[k].
    bool reboundedOnNet(std::size_t k) const { return m_netContacts[k].bounce > 0.0; }

    /// A ball pushed out of the room by a sweep back on its surfaces (those of `walls`, a bit a
    /// plane), its speed into them taken away.
    static void keepInRoom(std::span<const Plane> planes, std::uint32_t walls, Ball& ball);

private:
    /// Each ball's contact with a piece of a net, its rule and, warm started, its contact as the
    /// last step left it (known again by the ball and the piece's bodies).
    void startOnNets(double dt);
    /// touchBalls between the piece's point and the ball or the other segment's point, each as a
    /// ball of its point's mass (each end carrying its weight of it), their pushes and impulses
    /// shared back to the ends.
    void touchNet(const NetContact& s, BallContact<double>& contact, const BallPairRule<double>& rule, bool first);

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
    NetPieces m_pieces;
    std::vector<BallPairRule<double>> m_netRules;
    std::vector<BallContact<double>> m_netContacts;
    /// The last step's contacts, by their bodies' world indices (first < second), in order.
    std::vector<std::pair<std::pair<std::size_t, std::size_t>, BallContact<double>>> m_remembered;
    /// The last step's contacts with pieces of nets, by the toucher's and the piece's bodies, in order.
    using NetKey = std::array<std::size_t, 5>;
    std::vector<std::pair<NetKey, BallContact<double>>> m_rememberedOnNets;
    NetKey keyOf(const NetContact& s) const
    {
        return {bodies[s.toucher.ends[0]], bodies[s.toucher.ends[1]], bodies[s.piece.ends[0]], bodies[s.piece.ends[1]],
                bodies[s.piece.ends[2]]};
    }
};

} // namespace pba::detail
