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
// would cost more than its contacts. Private to the core.
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "ball.hpp"
#include "particle_grid.hpp"

namespace pba::detail {

/// A ball against a piece of a net, at the piece's point nearest it.
struct BallOnNet {
    /// The piece's balls: a segment's two (its third the second again, of weight 0), or a triangle's three.
    std::array<std::uint32_t, 3> ends{};
    std::array<double, 3> weights{}; ///< the point's, on its ends (summing to 1)
    std::uint32_t ball = 0;
    double radius = 0.0; ///< the piece's thickness there
};

class NetPieces {
public:
    /// The balls touching pieces of nets they are not part of, into `out`, ball by ball in index
    /// order (so the same on any thread count). `segments` pairs of balls, `triangles` triples;
    /// `generation` changes when they do (the nets are worked out again then).
    void find(std::span<const Ball> balls, std::span<const std::pair<std::uint32_t, std::uint32_t>> segments,
              std::span<const std::array<std::uint32_t, 3>> triangles, std::uint64_t generation,
              std::vector<BallOnNet>& out);

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
    /// Whether `ball` touches piece p at an inner point, deeper than the piece's own balls do:
    /// then `contact` is it.
    static bool touching(std::span<const Ball> balls, const Piece& p, std::uint32_t ball, BallOnNet& contact);

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
