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
//
// A ball meets the segments of the ropes and cloths it is not part of too (each spring between
// two balls that runs past no third: spring_neighbours.hpp), as rigid bodies do: as a rod as
// thick as the segment's balls but no thicker than half the gap between them, at its point
// nearest the ball, where the segment lies deeper in it than its two balls do. Its push and
// impulses go to the segment's two balls by their shares of that point (a rod without mass), so
// a ball smaller than the gap between a sheet's balls lands on the sheet instead of falling
// through it. A net's own far balls meet it by their balls alone (the self-collision).
#include <array>
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

/// A ball against a segment between two other balls, at the segment's point nearest it.
struct BallOnSegment {
    std::uint32_t a = 0, b = 0; ///< the segment's balls
    std::uint32_t ball = 0;
    double t = 0.0;      ///< the point, along the segment from a
    double radius = 0.0; ///< the segment's thickness there
};

struct BallContacts {
    ParticleGrid grid;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    std::vector<Ball> balls;
    std::vector<std::size_t> bodies; ///< each ball's world index
    /// The nets' segments, as pairs of balls (indices into `balls`); set before solve, with the
    /// generation of the lists they come from (the nets are worked out again when it changes).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> segments;
    std::uint64_t segmentsGeneration = 0;
    /// The balls against segments of the last solve.
    std::vector<BallOnSegment> onSegments;

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
        findOnSegments();
        if (pairs.empty() && onSegments.empty()) {
            m_remembered.clear();
            m_rememberedOnSegments.clear();
            return;
        }
        findWalls(planes, largest);
        startContacts(dt);
        startOnSegments(dt);
        for (int sweep = 0; sweep < sweeps; ++sweep) {
            for (std::size_t k = 0; k < pairs.size(); ++k) {
                Ball& a = balls[pairs[k].first];
                Ball& b = balls[pairs[k].second];
                touchBalls(a.x, a.v, b.x, b.v, m_contacts[k], m_rules[k], sweep == 0);
            }
            for (std::size_t k = 0; k < onSegments.size(); ++k)
                touchSegment(onSegments[k], m_segmentContacts[k], m_segmentRules[k], sweep == 0);
            for (const auto& [k, walls] : nearWall)
                keepInRoom(planes, walls, balls[k]);
        }
        remember();
    }

    /// Whether pair k, of the last solve, arrived fast enough to rebound (a bounce, as the room's
    /// and the rigid bodies' contacts count one), rather than rest.
    bool rebounded(std::size_t k) const { return m_contacts[k].bounce > 0.0; }
    /// The same for onSegments[k].
    bool reboundedOnSegment(std::size_t k) const { return m_segmentContacts[k].bounce > 0.0; }

    /// A ball pushed out of the room by a sweep back on its surfaces (those of `walls`, a bit a
    /// plane), its speed into them taken away.
    static void keepInRoom(std::span<const Plane> planes, std::uint32_t walls, Ball& ball);

private:
    /// The balls against other nets' segments (onSegments), ball by ball in index order.
    void findOnSegments();
    /// Each ball's net (m_net), and whether any ball asks for segments (m_asking).
    void findNets();
    /// The segments that a ball of the smallest radius could meet deeper than their balls do,
    /// into m_kept. False if none, or if no ball asks.
    bool keepSegments();
    /// Whether `ball` touches segment s of m_kept at an inner point, deeper than the segment's two
    /// balls do: then m_touching is the contact.
    bool touchingSegment(std::uint32_t s, std::uint32_t ball);
    /// Each ball's contact with a segment, its rule and, warm started, its contact as the last
    /// step left it (known again by the ball and the segment's two bodies).
    void startOnSegments(double dt);
    /// The segment's point moved by dx and its velocity changed by dv: each end's share of it.
    void shareOut(const BallOnSegment& s, const dvec3& dx, const dvec3& dv);
    /// touchBalls between the ball and the segment's point, as a ball of the point's mass
    /// (each end carries its share of it), its push and impulses shared back to the two ends.
    void touchSegment(const BallOnSegment& s, BallContact<double>& contact, const BallPairRule<double>& rule, bool first);

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
    ParticleGrid m_segmentGrid; ///< of the kept segments, each as the ball around it
    BallOnSegment m_touching;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> m_kept;
    std::vector<dvec3> m_segmentMiddle;
    std::vector<double> m_segmentReach; ///< from its middle: half its length and its thicker ball
    double m_largestSegmentReach = 0.0;
    static constexpr std::uint32_t kNoNet = ~std::uint32_t(0);
    std::vector<std::uint32_t> m_net;   ///< each ball's net (its first ball's index), or kNoNet
    std::uint64_t m_netsOf = ~std::uint64_t(0); ///< the segments' generation m_net was found for
    bool m_twoNets = false, m_asking = false;
    std::vector<std::uint32_t> m_found; ///< a query's segments
    std::vector<BallPairRule<double>> m_segmentRules;
    std::vector<BallContact<double>> m_segmentContacts;
    /// The last step's contacts, by their bodies' world indices (first < second), in order.
    std::vector<std::pair<std::pair<std::size_t, std::size_t>, BallContact<double>>> m_remembered;
    /// The last step's contacts with segments, by the ball's and the segment's bodies, in order.
    using SegmentKey = std::array<std::size_t, 3>;
    std::vector<std::pair<SegmentKey, BallContact<double>>> m_rememberedOnSegments;
    SegmentKey keyOf(const BallOnSegment& s) const { return {bodies[s.ball], bodies[s.a], bodies[s.b]}; }
};

} // namespace pba::detail
