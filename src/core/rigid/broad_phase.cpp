#include "rigid/broad_phase.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

namespace pba::rigid {

namespace {

using Cell = BroadPhase::Cell;

double largestSide(const Box& b) { return std::max({b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z}); }

} // namespace

double BroadPhase::cellSize(std::span<const Box> boxes, std::span<const std::uint8_t> isPoint)
{
    m_sizes.clear();
    for (std::size_t i = 0; i < boxes.size(); ++i)
        if (!isPoint[i])
            m_sizes.push_back(largestSide(boxes[i]));
    if (m_sizes.empty())
        return 1.0;
    // Twice the median: a body moving fast swells its box, and one past a cell's size is
    // tested against every body.
    auto middle = m_sizes.begin() + std::ptrdiff_t(m_sizes.size() / 2);
    std::nth_element(m_sizes.begin(), middle, m_sizes.end());
    return std::max(2.0 * *middle, 1e-9);
}

void BroadPhase::fillGrid(std::span<const Box> boxes, std::span<const Motion> motion,
                          std::span<const std::uint8_t> isPoint)
{
    const std::size_t n = boxes.size();
    m_large.assign(n, 0);
    m_largeList.clear();
    m_widest = 0.0;
    std::size_t small = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (isPoint[i]) {
            // Not in the grid: it looks there for its partners (a fixed one is found by them).
            if (motion[i] == Motion::Static) {
                m_large[i] = 1;
                m_largeList.push_back(std::uint32_t(i));
            }
        } else if (const double side = largestSide(boxes[i]); side > m_cell) {
            m_large[i] = 1;
            m_largeList.push_back(std::uint32_t(i));
        } else {
            ++small;
            m_widest = std::max(m_widest, side);
        }
    }
    sortIntoBuckets(boxes, motion, isPoint, small);
}

void BroadPhase::sortIntoBuckets(std::span<const Box> boxes, std::span<const Motion> motion,
                                 std::span<const std::uint8_t> isPoint, std::size_t small)
{
    // A counting sort: the bodies of a bucket stay in index order.
    const std::size_t n = boxes.size();
    const std::uint32_t buckets = detail::bucketsFor(2 * small);
    const std::uint32_t mask = buckets - 1;
    m_cells.resize(n);
    m_bucket.resize(n);
    m_bucketStart.assign(buckets + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        m_cells[i] = detail::cellOf(boxes[i].min, m_cell);
        if (!m_large[i] && !isPoint[i]) {
            m_bucket[i] = detail::bucketOf(m_cells[i], mask);
            ++m_bucketStart[m_bucket[i] + 1];
        }
    }
    for (std::uint32_t k = 0; k < buckets; ++k)
        m_bucketStart[k + 1] += m_bucketStart[k];
    m_entries.resize(small);
    m_next.assign(m_bucketStart.begin(), m_bucketStart.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
        if (!m_large[i] && !isPoint[i])
            m_entries[m_next[m_bucket[i]]++] = Entry{boxes[i], m_cells[i], std::uint32_t(i), motion[i] == Motion::Awake};
}

template <class F>
void BroadPhase::forEachInGrid(const Box& box, F&& f) const
{
    const std::uint32_t mask = std::uint32_t(m_bucketStart.size() - 2);
    // A body in the grid overlapping the box has its lowest corner no further below the box's
    // lowest corner than the widest of them is wide, and no further than its highest.
    const Cell lo = detail::cellOf(box.min - m_widest, m_cell), hi = detail::cellOf(box.max, m_cell);
    for (std::int64_t x = lo.x; x <= hi.x; ++x)
        for (std::int64_t y = lo.y; y <= hi.y; ++y)
            for (std::int64_t z = lo.z; z <= hi.z; ++z) {
                const Cell cell{x, y, z};
                const std::uint32_t h = detail::bucketOf(cell, mask);
                for (std::uint32_t e = m_bucketStart[h]; e < m_bucketStart[h + 1]; ++e) {
                    const Entry& entry = m_entries[e];
                    // Another cell of the same bucket would find it twice.
                    if (entry.cell == cell && box.overlaps(entry.box))
                        f(entry);
                }
            }
}

void BroadPhase::partnersOf(std::uint32_t k, const Box& box, std::span<const Box> boxes,
                            std::span<const std::uint8_t> isPoint, std::vector<BodyPair>& pairs) const
{
    const auto add = [&](std::uint32_t j) {
        if (j != k && !(isPoint[j] && isPoint[k]))
            pairs.push_back({BodyIndex(std::min(j, k)), BodyIndex(std::max(j, k))});
    };
    // A box of more cells than the grid has bodies (a body flung far in one step) reads them all.
    const dvec3 cells = (box.max - box.min) / m_cell + 2.0;
    if (!(cells.x * cells.y * cells.z <= double(m_entries.size()))) {
        for (const Entry& entry : m_entries)
            if (box.overlaps(entry.box))
                add(entry.body);
    } else {
        forEachInGrid(box, [&](const Entry& entry) { add(entry.body); });
    }
    for (const std::uint32_t l : m_largeList)
        if (box.overlaps(boxes[l]))
            add(l);
}

void BroadPhase::pairsOfSmall(std::span<const Box> boxes, std::span<const Motion> motion,
                              std::span<const std::uint8_t> isPoint, std::vector<BodyPair>& pairs)
{
    const std::size_t n = boxes.size();
    // Fixed chunks, whatever the thread count: each chunk's pairs are its own.
    constexpr std::size_t kChunk = 512;
    m_chunks.resize((n + kChunk - 1) / kChunk);
    tbb::parallel_for(std::size_t(0), m_chunks.size(), [&](std::size_t chunk) {
        auto& out = m_chunks[chunk];
        out.clear();
        const std::size_t end = std::min(n, (chunk + 1) * kChunk);
        for (std::size_t i = chunk * kChunk; i < end; ++i) {
            // Pairs are found from their awake bodies: a sleeping pile's own pairs are carried
            // over by the contact cache, and its bodies are only looked up as partners.
            if (m_large[i] || motion[i] != Motion::Awake)
                continue;
            forEachInGrid(boxes[i], [&](const Entry& entry) {
                // Two awake bodies: once, from the first (a point is never in the grid, so it
                // finds every partner itself).
                const std::uint32_t j = entry.body;
                if (j != i && !(j < i && entry.awake && !isPoint[i]))
                    out.push_back({BodyIndex(std::min<std::size_t>(i, j)), BodyIndex(std::max<std::size_t>(i, j))});
            });
        }
    });
    for (const auto& chunk : m_chunks)
        pairs.insert(pairs.end(), chunk.begin(), chunk.end());
}

void BroadPhase::pairsOfLarge(std::span<const Box> boxes, std::span<const Motion> motion,
                              std::span<const std::uint8_t> isPoint, std::vector<BodyPair>& pairs)
{
    for (const std::uint32_t l : m_largeList)
        for (std::size_t k = 0; k < boxes.size(); ++k) {
            if (k == l || (m_large[k] && k < l)) // two large bodies: once
                continue;
            if (isPoint[l] && isPoint[k])
                continue;
            if (motion[l] != Motion::Awake && motion[k] != Motion::Awake)
                continue;
            if (boxes[l].overlaps(boxes[k]))
                pairs.push_back({BodyIndex(std::min<std::size_t>(l, k)), BodyIndex(std::max<std::size_t>(l, k))});
        }
}

void BroadPhase::findPairs(std::span<const Box> boxes, std::span<const Motion> motion,
                           std::span<const std::uint8_t> isPoint, std::vector<BodyPair>& pairs)
{
    pairs.clear();
    if (boxes.empty())
        return;
    m_cell = cellSize(boxes, isPoint);
    fillGrid(boxes, motion, isPoint);
    pairsOfSmall(boxes, motion, isPoint, pairs);
    pairsOfLarge(boxes, motion, isPoint, pairs);
    std::sort(pairs.begin(), pairs.end());
}

} // namespace pba::rigid
