#pragma once
// The pieces of ropes and cloths between their balls, which other balls meet: each segment (a
// spring between two balls that runs past no third: spring_neighbours.hpp) and each triangle of
// three segments (a cloth's cell halves, as it is drawn), as thick as their balls but no thicker
// than half the gap between them. A ball that comes between a net's balls meets the piece at its
// point nearest the ball, where the piece lies deeper in it than the piece's own balls do; the
// contact's push and impulses go to the piece's balls by their weights at that point (a piece
// without mass), so a ball smaller than the holes of a sheet lands on it instead of falling
// through. Only the balls of no net, or of another net, ask: a net's own far balls meet it by
// their balls alone (the self-collision), and asking every ball of a cloth for its own pieces
// would cost more than its contacts. Two nets' segments that cross between their balls meet at
// their nearest points in the same way, each side's share going to its own two balls, so a rope
// dropped across another hangs on it. A ball that met a piece within the step, on its way there,
// is found too (findPasses), and met at that time (ball_impacts.hpp). Private to the core.
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "balls/ball.hpp"
#include "balls/particle_grid.hpp"

namespace pba::detail {

/// Balls acting as one point: a ball alone, or a piece's point by its weights on the piece's balls.
struct NetPoint {
    std::array<std::uint32_t, 3> ends{}; ///< its balls (those past `count` repeat the last, of weight 0)
    std::array<double, 3> weights{};     ///< summing to 1
    int count = 1;                       ///< 1: a ball, 2: a segment's point, 3: a triangle's
    double radius = 0.0;                 ///< the ball's, or the piece's thickness there

    static NetPoint ball(std::uint32_t b, double radius) { return {{b, b, b}, {1.0, 0.0, 0.0}, 1, radius}; }
};

/// The point as one ball: its balls' places (now and at the step's start), velocities and
/// materials by its weights, its inverse mass theirs by the squares of the weights (what a push
/// at it moves it by), its radius its own; met in substeps, or sprung, if any of its balls is.
inline Ball asBall(std::span<const Ball> balls, const NetPoint& p)
{
    Ball b;
    b.radius = p.radius;
    b.cor = b.friction = 0.0;
    for (std::size_t e = 0; e < 3; ++e) {
        const Ball& end = balls[p.ends[e]];
        const double w = p.weights[e];
        b.x += w * end.x;
        b.v += w * end.v;
        b.start += w * end.start;
        b.inverseMass += w * w * end.inverseMass;
        b.cor += w * end.cor;
        b.friction += w * end.friction;
        b.restingSpeed = std::max(b.restingSpeed, end.restingSpeed);
        b.metInSubsteps = b.metInSubsteps || end.metInSubsteps;
        b.sprung = b.sprung || end.sprung;
    }
    return b;
}

/// A point of balls moved by dx and its velocity changed by dv: each ball's share of it, its
/// weight times its inverse mass over the point's (a ball alone moves by dx itself, to the bit).
inline void shareOut(std::span<Ball> balls, const NetPoint& p, const dvec3& dx, const dvec3& dv)
{
    if (p.count == 1) {
        Ball& ball = balls[p.ends[0]];
        ball.x += dx;
        ball.v += dv;
        return;
    }
    const double w = asBall(balls, p).inverseMass;
    if (!(w > 0.0))
        return;
    const dvec3 moved = dx / w, pushed = dv / w;
    for (std::size_t e = 0; e < 3; ++e) {
        Ball& end = balls[p.ends[e]];
        end.x += p.weights[e] * end.inverseMass * moved;
        end.v += p.weights[e] * end.inverseMass * pushed;
    }
}

/// A ball of no net or of another net against a piece of a net, at the piece's point nearest it;
/// or a segment of one net crossing a segment of another between their balls, at their nearest
/// points.
struct NetContact {
    NetPoint piece;
    NetPoint toucher; ///< the ball, or the other segment's point
};

/// A ball that met a piece of a net it is not part of within the step, on its way from where it
/// started: when (a fraction of the step), and the piece's point it met.
struct PiecePass {
    double t = 0.0;
    std::uint32_t ball = 0;
    NetPoint piece;
};

class NetPieces {
public:
    /// The balls touching pieces of nets they are not part of, into `out`, ball by ball in index
    /// order (so the same on any thread count). `segments` pairs of balls, `triangles` triples;
    /// `generation` changes when they do (the nets are worked out again then).
    void find(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments,
              std::span<const std::array<std::uint32_t, 3>> triangles, std::uint64_t generation,
              std::vector<NetContact>& out);
    /// The balls that met a piece of a net they are not part of within the step, each ball's
    /// path and each of the piece's balls' the straight line from its start (ball_impacts.hpp),
    /// into `out`, ball by ball in index order.
    void findPasses(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments,
                    std::span<const std::array<std::uint32_t, 3>> triangles, std::uint64_t generation,
                    std::vector<PiecePass>& out);

private:
    struct Piece {
        std::array<std::uint32_t, 3> ends{};
        int count = 2; ///< 2: a segment, 3: a triangle
    };
    /// Each ball's net (m_net), and whether any ball asks (m_asking).
    void findNets(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments);
    /// The pieces that a ball of the smallest radius could meet deeper than their balls do, into
    /// m_kept, with where each is and how far it reaches. False if none.
    bool keep(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments,
              std::span<const std::array<std::uint32_t, 3>> triangles);
    /// The nets worked out (again, if `generation` changed), the pieces kept and their grid
    /// built; false if no ball asks or no piece is kept.
    bool ready(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments,
               std::span<const std::array<std::uint32_t, 3>> triangles, std::uint64_t generation);
    /// Whether `ball` may meet pieces (of no net, or of one of two nets or more).
    bool asks(std::uint32_t ball) const { return m_net[ball] == kNoNet || m_twoNets; }
    /// Whether `ball` met piece p at an inner point within the step, on the straight paths:
    /// then `pass` is it.
    static bool passing(std::span<const Ball> balls, const Piece& p, std::uint32_t ball, PiecePass& pass);
    /// Whether `ball` touches piece p at an inner point, deeper than the piece's own balls do:
    /// then `contact` is it.
    static bool touching(std::span<const Ball> balls, const Piece& p, std::uint32_t ball, NetContact& contact);
    /// Whether segments p and q cross between their balls, nearer than their thicknesses and
    /// deeper than either's balls lie against the other: then `contact` is it.
    static bool crossing(std::span<const Ball> balls, const Piece& p, const Piece& q, NetContact& contact);

    static constexpr std::uint32_t kNoNet = ~std::uint32_t(0);
    std::vector<std::uint32_t> m_net; ///< each ball's net (its first ball's index), or kNoNet
    std::uint64_t m_netsOf = ~std::uint64_t(0); ///< the generation m_net was found for
    bool m_twoNets = false, m_asking = false;
    std::vector<Piece> m_kept;
    std::vector<dvec3> m_centre;
    std::vector<double> m_reach; ///< from its centre: its farthest end, and its thickest ball
    double m_largestReach = 0.0;
    ParticleGrid m_grid; ///< of the kept pieces, each as the ball around it
    std::vector<std::uint32_t> m_found;
};

} // namespace pba::detail
