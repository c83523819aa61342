#pragma once
// A colliding swarm's grains against each other and the room, in the swarm's own precision
// (float) and on all cores. Private to the core.
//
// Each step the grains are sorted by the cell of a grid as wide as a grain (a counting sort;
// the cells of the grains' bounding box numbered x-major, or hashed when that box holds far
// more cells than grains), so that the grains of a cell, and of neighbouring cells, lie close
// in memory. The touching pairs (i < j in that order) are listed slab by slab, a slab being the
// grains of a fixed number of cell columns along x. A pair of slab k touches grains of slabs k
// and k + 1 only, so the even slabs' pairs share no grain, nor do the odd slabs': a sweep solves
// the even slabs side by side, then the odd ones, each slab's pairs in order (Gauss-Seidel
// within a slab). The slabs come from the grains' positions alone, so every result is the same
// on any thread count.
//
// The rule for a pair is the particles' (BallContacts::touch) for equal masses: the overlap is
// split in half, the approach speed that restitution does not give back is taken away (all of
// it in a resting contact), and Coulomb friction takes up to mu times that from the sliding.
// The room has friction too: a grain on a wall loses up to mu times the wall's push from its
// sliding, the push counting its weight's share of the step (which the swarm's own collision
// with the room took away before the contacts run) and what the sweeps press into the wall.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "pba/collision.hpp"

namespace pba {
class Swarm;
}

namespace pba::detail {

struct GrainRule {
    float radius = 0.0f;
    float cor = 0.0f;
    float friction = 0.0f;
    float restingSpeed = 0.0f; ///< what gravity gives a grain in one step, |g| dt
    float dt = 0.0f;
};

class GrainContacts {
public:
    std::unique_ptr<GrainContacts> clone() const { return std::make_unique<GrainContacts>(*this); }

    /// `sweeps` sweeps over the touching grains of `swarm`, with `room` the room's planes
    /// already moved a radius inwards (ballPlanes); writes the grains back.
    void solve(Swarm& swarm, std::span<const PlaneT<float>> room, const GrainRule& rule, int sweeps);

    /// The touching pairs the last solve found.
    std::size_t pairCount() const;

private:
    using Vec = Vec3<float>;
    struct Grid {
        Vec3<std::int64_t> lo{0}, dims{0};
        float spacing = 1.0f;
        std::size_t cells = 0;
        bool hashed = false;
        std::int64_t slabWidth = 1; ///< cell columns along x per slab
    };

    void gather(const Swarm& swarm, float dt);
    void plan(float spacing);
    void sortByCell(const Swarm& swarm);
    void findPairs(std::size_t slab);
    void sweep(std::span<const PlaneT<float>> room, const GrainRule& rule, bool first);
    /// fn(a, b) for every pair: the even slabs' side by side, then the odd slabs'.
    template <class F>
    void forEachPairInColours(F&& fn);
    Vec3<std::int64_t> cellOf(const Vec& x) const;
    std::size_t keyOf(const Vec3<std::int64_t>& cell) const;

    Grid m_grid;
    std::vector<Vec> m_x, m_v;                ///< the grains in cell order
    std::vector<Vec> m_x0;                    ///< where each started the step
    std::vector<std::uint32_t> m_order;       ///< cell order -> swarm index
    std::vector<std::uint32_t> m_key;         ///< swarm index -> cell (or bucket)
    std::vector<std::uint32_t> m_cellStart;   ///< cell c's grains are [m_cellStart[c], m_cellStart[c + 1])
    std::vector<std::size_t> m_slabStart;     ///< slab k's grains are [m_slabStart[k], m_slabStart[k + 1])
    std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> m_pairs; ///< per slab
    float m_reach = 0.0f;                     ///< two radii
};

} // namespace pba::detail
