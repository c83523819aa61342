#pragma once
// The velocity sweeps of a large island four contacts at a time (Box2D v3's wide solver, in 3D):
// the contacts are coloured so that no moving body is in two contacts of one colour, each
// colour's contacts are packed four to a block, one a lane, and a block's rows are solved with
// one instruction for the four. A sweep visits the colours in order and, after them, the few
// contacts no colour took, one at a time. A contact's arithmetic is the one-at-a-time sweep's, in
// single precision (the bodies' velocities are read into floats and the changes added back in
// double); only the order of the contacts differs, the same on any number of threads.
//
// A sweep over a heap's rows one at a time waited on each row's result before the next (a
// body's velocity is read, changed and read again); four lanes of unrelated bodies do not.
// Private to the core.
#include <cstdint>
#include <span>
#include <vector>

#include "rigid/contact.hpp"
#include "rigid/float4.hpp"
#include "rigid/solver_body.hpp"
#include "rigid/velocity_rows.hpp"

namespace pba::rigid {

class WideContactRows {
public:
    /// Islands with fewer contacts are swept one contact at a time: too few for full blocks.
    static constexpr std::size_t kFewest = 64;

    /// Packs `contacts`, as colour() last coloured them, with their rows' impulses as they are now
    /// (after the warm start); lists in `leftOver` the indices of those no colour took, in order.
    void build(std::span<const IslandContact> contacts, std::span<const VelocityRows> rows, std::span<const SolverBody> bodies,
               std::vector<std::uint32_t>& leftOver);
    bool empty() const { return m_blocks.empty(); }
    /// One sweep over the blocks; the largest change of an impulse and the largest normal
    /// impulse into `change` and `largest`.
    void sweep(std::span<SolverBody> bodies, double& change, double& largest);
    static constexpr int kColours = 24; ///< as Box2D v3's graph: a heap of dice takes eight or nine
    /// Colours the contacts so that no moving body is in two of one colour (fewer than kFewest:
    /// none, all left over). Once a step, before the collision pass and build.
    void colour(std::span<const IslandContact> contacts, std::span<const SolverBody> bodies);
    /// The impulses back into the rows they came from.
    void storeImpulses(std::span<VelocityRows> rows) const;
    /// The rows' impulses into the blocks (after a pass that worked on the rows themselves).
    void loadImpulses(std::span<const VelocityRows> rows);
    /// The contacts (indices into build's) in the order a sweep visits them, four lanes a block
    /// (kEmptyLane where a block has fewer).
    std::vector<std::uint32_t> order() const;
    static constexpr std::uint32_t kEmptyLane = 0xffffffffu;

private:
    /// One row of four points (the normal, or a tangent), one a lane: each vector's x, y and z
    /// of the four, as the sweep loads them.
    struct WideRow {
        alignas(16) float u[3][4];
        alignas(16) float momentA[3][4], momentB[3][4];
        alignas(16) float turnA[3][4], turnB[3][4];
        alignas(16) float mass[4], impulse[4];
    };
    struct Slot {
        Slot() {} // left unset: build writes every lane (zeroing each step's 800 bytes a slot cost more)
        WideRow row[3]; ///< the normal, then the two tangents
        alignas(16) float target[4];
        std::uint32_t source[4]; ///< each lane's index into the rows, or kEmptyLane
    };
    struct Block {
        BodyIndex body[2][4]; ///< A's and B's, by lane (an empty lane's: its first lane's)
        std::uint32_t contact[4]; ///< each lane's index into build's contacts, or kEmptyLane
        bool moves[2][4];
        Float4 friction, inverseMass[2];
        std::uint32_t firstSlot = 0, slots = 0;
    };
    /// One block of up to four contacts of one colour (indices into contacts).
    void pack(std::span<const IslandContact> contacts, std::span<const VelocityRows> rows, std::span<const SolverBody> bodies,
              std::span<const std::uint32_t> lanes);
    void sweepBlock(const Block& block, std::span<SolverBody> bodies, Float4& changed, Float4& most);
    void solveFriction(Slot& slot, const Block& block, Vec4x3 (&v)[2], Vec4x3 (&w)[2], Float4& change);
    void solveNormal(Slot& slot, const Block& block, Vec4x3 (&v)[2], Vec4x3 (&w)[2], Float4& change,
                     Float4& largest);

    std::vector<Block> m_blocks;
    std::vector<Slot> m_slots;
    std::vector<std::uint32_t> m_used;   ///< per body, the colours its contacts have taken
    std::vector<std::uint8_t> m_colour;  ///< per contact
    std::vector<std::uint32_t> m_byColour; ///< the contacts, colour by colour
    std::vector<std::uint32_t> m_colourContacts = std::vector<std::uint32_t>(kColours + 2, 0); ///< colour c's in m_byColour: [c], [c + 1]
    std::vector<std::uint32_t> m_order;    ///< scratch: one colour's contacts
};

} // namespace pba::rigid
