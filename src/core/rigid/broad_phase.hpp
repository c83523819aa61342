#pragma once
// The broad phase: which bodies' boxes overlap, so that the narrow phase looks only at those
// pairs. A hashed uniform grid (as in Müller's "Ten Minute Physics" hashing): each body of
// ordinary size goes into the cell of its box's lowest corner, with cells twice as large as the
// median body, and looks for partners in the cells around it; the few bodies larger than a cell
// (a floor slab, a ramp) are tested against every body. Fixed bodies of ordinary size are in the
// grid too: a board of 500 pegs would otherwise test every peg against every body, every step.
// A grid suits a pile of like bodies on a floor,
// where a sort-and-sweep along one axis would meet every body sharing a slice of the floor.
// Point bodies (particles: a cloth's thousands, each far smaller than a die) are not put in the
// grid and do not size its cells: each looks for the bodies around it, never for another point.
#include <cstdint>
#include <span>
#include <vector>

#include "pba/math.hpp"
#include "rigid/contact.hpp"
#include "balls/spatial_hash.hpp"

namespace pba::rigid {

struct Box {
    dvec3 min{0.0};
    dvec3 max{0.0};
    bool overlaps(const Box& o) const
    {
        return min.x <= o.max.x && o.min.x <= max.x && min.y <= o.max.y && o.min.y <= max.y && min.z <= o.max.z &&
               o.min.z <= max.z;
    }
};

enum class Motion : std::uint8_t { Static, Asleep, Awake };

struct BodyPair {
    BodyIndex a = 0, b = 0; ///< a < b
    friend bool operator<(const BodyPair& p, const BodyPair& q) { return p.a != q.a ? p.a < q.a : p.b < q.b; }
    friend bool operator==(const BodyPair& p, const BodyPair& q) = default;
};

class BroadPhase {
public:
    using Cell = detail::GridCell;

    /// The pairs whose boxes overlap and of which at least one body is awake, in increasing
    /// order (the same whatever the thread count); no pair of two points (isPoint, per body).
    void findPairs(std::span<const Box> boxes, std::span<const Motion> motion, std::span<const std::uint8_t> isPoint,
                   std::vector<BodyPair>& pairs);

    /// Appends a pair of body k with each body whose box overlaps `box` (k's own, widened), as
    /// findPairs would have paired them (points and sleeping bodies too; some it has already).
    void partnersOf(std::uint32_t k, const Box& box, std::span<const Box> boxes, std::span<const std::uint8_t> isPoint,
                    std::vector<BodyPair>& pairs) const;

private:
    /// Calls f(entry) for each body in the grid whose box overlaps `box`, once.
    template <class F>
    void forEachInGrid(const Box& box, F&& f) const;
    double cellSize(std::span<const Box> boxes, std::span<const std::uint8_t> isPoint);
    void fillGrid(std::span<const Box> boxes, std::span<const Motion> motion, std::span<const std::uint8_t> isPoint);
    /// The `small` bodies in the grid into the hash table's buckets.
    void sortIntoBuckets(std::span<const Box> boxes, std::span<const Motion> motion,
                         std::span<const std::uint8_t> isPoint, std::size_t small);
    void pairsOfSmall(std::span<const Box> boxes, std::span<const Motion> motion, std::span<const std::uint8_t> isPoint,
                      std::vector<BodyPair>& pairs);
    void pairsOfLarge(std::span<const Box> boxes, std::span<const Motion> motion, std::span<const std::uint8_t> isPoint,
                      std::vector<BodyPair>& pairs);

    double m_cell = 1.0;   ///< the grid's cells' side: a body with a longer one is large
    double m_widest = 0.0; ///< the longest side of a body in the grid
    std::vector<std::uint8_t> m_large;        ///< per body: tested against every body
    std::vector<std::uint32_t> m_largeList;
    std::vector<std::uint32_t> m_bucketStart; ///< the hash table: bucket k holds m_entries[start[k], start[k+1])
    /// A body in the grid, with what a partner's test reads of it: a bucket's bodies are read in
    /// a row instead of each through three lists.
    struct Entry {
        Box box;
        Cell cell;
        std::uint32_t body = 0;
        bool awake = false;
    };
    std::vector<Entry> m_entries;
    std::vector<double> m_sizes;
    std::vector<Cell> m_cells; ///< each body's: the cell of its box's lowest corner
    std::vector<std::uint32_t> m_bucket; ///< each grid body's: its cell's bucket
    std::vector<std::uint32_t> m_next;   ///< scratch: each bucket's next free entry
    std::vector<std::vector<BodyPair>> m_chunks;
};

} // namespace pba::rigid
