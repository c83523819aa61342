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
// A pair's rule is every ball's (ball_rule.hpp), for equal masses: sequential impulses with
// static friction held by an anchor. The room holds a grain on its walls the same way, bounded by
// the walls' push over the sweeps, the grain's weight counted (the swarm's own collision with the
// room takes it away before the contacts run): without it, a mound crept outwards by a few
// micrometres a step for as long as it stood, from 45 degrees as it formed to 21 at 8 s.
//
// Each pair starts from what it did the step before (warm starting, as Box2D's contacts do): its
// normal and sliding changes are given to the grains before the sweeps, so a heap's weight, which
// Gauss-Seidel sweeps carry down only a few layers a step, is there from the start. A pair is
// known again by its grains' places in the last step's cell order: this step's order is that
// order sorted anew by cell (stably), so a resting heap's grains keep their places and the last
// step's pairs are read nearly in order. A grain that moved more than a reach since (or a swarm
// replaced) starts its pairs from zero.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "balls/ball_rule.hpp"
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

/// Two touching grains (in cell order), and what their contact has done over the step's sweeps
/// so far (ball_rule.hpp).
struct GrainPair {
    std::uint32_t a = 0, b = 0;
    BallContact<float> contact;
};

/// A grain against the room's walls over the step's sweeps: where their static friction holds it
/// (its slip since it came to a wall, less where it was then: its position added, the slip now),
/// the speed they pushed it out with (m/s), and how much their friction has taken from its
/// sliding (m/s) and its slip (m); whether it touched one.
struct GrainWall {
    Vec3<float> anchor{0.0f};
    float push = 0.0f, slowed = 0.0f, held = 0.0f;
    bool touched = false;
};

/// A pair as the next step finds it again: its second grain's place in this step's cell order
/// (the first's is where it is listed) and its normal and sliding changes.
struct RememberedPair {
    std::uint32_t b = 0;
    float normal = 0.0f;
    Vec3<float> tangent{0.0f};
    Vec3<float> slip{0.0f}; ///< how far b has slid over a since they met
};

/// What one swarm's contacts did last step: the cell order, where each grain (in that order)
/// ended, and the pairs by their first grain, grain j's being pairs[row[j], row[j + 1]).
struct GrainMemory {
    std::vector<std::uint32_t> order;
    std::vector<Vec3<float>> end;
    std::vector<std::uint32_t> row;
    std::vector<RememberedPair> pairs;
    std::vector<Vec3<float>> wallSlip; ///< each grain's slip on the walls it touched (zero: none)
};

class GrainContacts {
public:
    std::unique_ptr<GrainContacts> clone() const { return std::make_unique<GrainContacts>(*this); }

    /// `sweeps` sweeps over the touching grains of `swarm`, the world's swarm number `slot` (whose
    /// last step's contacts it remembers), with `room` the room's planes already moved a radius
    /// inwards (ballPlanes); writes the grains back.
    void solve(Swarm& swarm, std::size_t slot, std::span<const PlaneT<float>> room, const GrainRule& rule,
               int sweeps);

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

    void gather(const Swarm& swarm, std::span<const PlaneT<float>> room, const GrainMemory& memory);
    void plan(float spacing);
    void sortByCell(const Swarm& swarm, const GrainMemory& memory);
    /// Each pair's impulses of the last step, where it had one, given to its grains.
    void warmStart(const GrainMemory& memory);
    void remember(GrainMemory& memory) const;
    void findPairs(std::size_t slab);
    void sweep(std::span<const PlaneT<float>> room, const GrainRule& rule, bool first);
    /// fn(pair) for every pair: the even slabs' side by side, then the odd slabs'.
    template <class F>
    void forEachPairInColours(F&& fn);
    Vec3<std::int64_t> cellOf(const Vec& x) const;
    std::size_t keyOf(const Vec3<std::int64_t>& cell) const;

    Grid m_grid;
    std::vector<Vec> m_x, m_v;                ///< the grains in cell order
    std::vector<std::uint32_t> m_nearWall; ///< each grain's walls within its reach this step, a bit a wall
    std::vector<GrainWall> m_walls;
    std::vector<std::uint32_t> m_order;       ///< cell order -> swarm index
    std::vector<std::uint32_t> m_key;         ///< the last step's cell order -> cell (or bucket)
    static constexpr std::uint32_t kNew = 0xffffffffu;
    std::vector<std::uint32_t> m_from;        ///< cell order -> place in the last step's (kNew: none)
    std::vector<std::uint32_t> m_previous;    ///< the sort's scratch
    std::vector<std::uint32_t> m_cellStart;   ///< cell c's grains are [m_cellStart[c], m_cellStart[c + 1])
    std::vector<std::size_t> m_slabStart;     ///< slab k's grains are [m_slabStart[k], m_slabStart[k + 1])
    std::vector<std::vector<GrainPair>> m_pairs; ///< per slab
    float m_reach = 0.0f;                     ///< two radii
    std::vector<GrainMemory> m_memory;        ///< per swarm slot
};

} // namespace pba::detail
