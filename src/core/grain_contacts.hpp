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
// A pair's rule is the particles' (BallContacts::touch) for equal masses, written as sequential
// impulses (Box2D's): the overlap is split in half, the normal speed change accumulated over the
// sweeps stays a push that leaves them apart at restitution times their approach (none in
// resting contact), and the accumulated change of their sliding stays within mu times it. Friction
// holds the step's displacement too: pushing grains apart along slanted normals alone lets a
// heap creep outwards by g dt^2 a step while its speeds stay near zero. The room has friction
// as well, bounded by its push over the sweeps, the grain's weight counted (the swarm's own
// collision with the room takes it away before the contacts run).
//
// Gauss-Seidel sweeps converge slowly through a deep heap: with 8 a step, a mound still creeps
// outwards for seconds after it formed (docs/scenes.md, granular).
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

/// Two touching grains (in cell order), and what their contact has done over the step's sweeps
/// so far: how far it pushed them apart (m), the change of their normal and sliding speeds (m/s).
struct GrainPair {
    std::uint32_t a = 0, b = 0;
    float pressed = 0.0f, normal = 0.0f, bounce = 0.0f;
    Vec3<float> tangent{0.0f};
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
    /// fn(pair) for every pair: the even slabs' side by side, then the odd slabs'.
    template <class F>
    void forEachPairInColours(F&& fn);
    Vec3<std::int64_t> cellOf(const Vec& x) const;
    std::size_t keyOf(const Vec3<std::int64_t>& cell) const;

    Grid m_grid;
    std::vector<Vec> m_x, m_v;                ///< the grains in cell order
    std::vector<Vec> m_x0;                    ///< where each started the step
    std::vector<std::uint32_t> m_nearWall; ///< each grain's walls within its reach this step, a bit a wall
    std::vector<float> m_push, m_slowed;      ///< the room's push on each this step (m/s), and its friction's
    std::vector<std::uint32_t> m_order;       ///< cell order -> swarm index
    std::vector<std::uint32_t> m_key;         ///< swarm index -> cell (or bucket)
    std::vector<std::uint32_t> m_cellStart;   ///< cell c's grains are [m_cellStart[c], m_cellStart[c + 1])
    std::vector<std::size_t> m_slabStart;     ///< slab k's grains are [m_slabStart[k], m_slabStart[k + 1])
    std::vector<std::vector<GrainPair>> m_pairs; ///< per slab
    float m_reach = 0.0f;                     ///< two radii
};

} // namespace pba::detail
