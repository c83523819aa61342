#pragma once
// Which particles of one spring mesh (a rope's, a cloth's) are too near each other along it to
// collide: a contact between them would fight the springs that hold them. Two particles with a
// radius are neighbours when a spring joins them, or when the shortest path of rest lengths
// between them through the springs is shorter than twice the sum of their radii (at rest they
// would overlap, or nearly, or only a sharp fold could bring them together, which the bending
// springs decide). Every other pair, far apart along one cloth or on two cloths, collides.
// From the same springs it lists the nets' segments and triangles, which rigid bodies and other
// balls meet between the balls (rigid/piece_contacts.hpp, net_pieces.hpp). Private to the core.
//
// Made once from the springs and the radii, and again only when either changes: a cloth's
// neighbours are its particles' few dozen nearest, held as sorted lists (compressed rows).
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "pba/clone_ptr.hpp"
#include "pba/force.hpp"

namespace pba::detail {

class SpringNeighbours {
public:
    /// The neighbours of the bodies with a radius (`radii`, one per body of the world, 0: none)
    /// through the springs among `forces`, made anew if the forces or the radii changed.
    void update(const std::vector<ClonePtr<Force>>& forces, std::span<const double> radii);
    /// Whether bodies a and b (world indices) are neighbours: never true for a body without springs.
    bool near(std::size_t a, std::size_t b) const;
    /// The nets' segments: each spring between two bodies with a radius (a < b) that does not
    /// run past a third along the net (a bending spring spans two segments, a shear spring
    /// crosses a cell), in the order of their first body.
    std::span<const std::pair<std::uint32_t, std::uint32_t>> segments() const { return m_segments; }
    /// The nets' triangles: three bodies (a < b < c) each two of which a segment joins (a cloth's
    /// cell halves, as the renderer draws them), in the order of their first two.
    std::span<const std::array<std::uint32_t, 3>> triangles() const { return m_triangles; }
    /// How many times the lists were made: a reader of segments() knows them again by it.
    std::uint64_t generation() const { return m_generation; }
    std::unique_ptr<SpringNeighbours> clone() const { return std::make_unique<SpringNeighbours>(*this); }

private:
    struct Edge {
        std::uint32_t to;
        double length;
    };
    void build(const std::vector<ClonePtr<Force>>& forces);
    std::span<const Edge> springsOf(std::size_t i) const;
    /// The rest length of the spring joining i and j, -1 if none does.
    double restLength(std::uint32_t i, std::uint32_t j) const;
    void findSegments();
    /// Whether segment c-d (c < d) crosses a segment before it in m_segments across one cell.
    bool crossesAnEarlierSegment(std::uint32_t c, std::uint32_t d) const;
    /// Body i's neighbours, found by a search of its springs out to the farthest they may lie.
    void nearOne(std::size_t i, double largestRadius, std::vector<std::uint32_t>& out);

    std::size_t m_forces = 0;
    std::vector<double> m_radii; ///< what the lists were made from
    bool m_made = false;
    std::vector<std::size_t> m_edgeStart; ///< body i's springs: m_edges[m_edgeStart[i], m_edgeStart[i + 1])
    std::vector<Edge> m_edges;
    std::vector<std::size_t> m_nearStart; ///< body i's neighbours: m_near[m_nearStart[i], m_nearStart[i + 1])
    std::vector<std::uint32_t> m_near;
    std::vector<double> m_distance; ///< the search's scratch, infinite where it has not been
    std::vector<std::pair<std::uint32_t, std::uint32_t>> m_segments;
    std::vector<std::array<std::uint32_t, 3>> m_triangles;
    std::uint64_t m_generation = 0;
};

} // namespace pba::detail
