#include "swarms/grain_contacts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "balls/ball_rule.hpp"
#include "surfaces/collision_rules.hpp"
#include "pba/swarm.hpp"

namespace pba::detail {

namespace {

using Vec = Vec3<float>;

/// Grains a task in the loops over all of them.
constexpr std::size_t kGrainBlock = 4096;

/// A grain pushed out of the room by a sweep put back on its walls, its speed into them taken
/// away, and its sliding along a wall it touches held back by friction, in position and speed.
/// Only the walls flagged in `near` (bit p for wall p; walls from the 33rd on always), the others
/// being too far for the sweeps to bring the grain to them.
inline void keepInRoom(std::span<const PlaneT<float>> room, std::uint32_t near, const GrainRule& rule, bool first,
                       Vec& x, Vec& v, GrainWall& wall)
{
    const float touching = 2.0f * rule.restingSpeed * rule.dt; // two steps' fall from rest
    for (std::size_t p = 0; p < room.size(); ++p) {
        if (!visits(near, p))
            continue;
        const PlaneT<float>& plane = room[p];
        const float depth = plane.distance(x);
        if (depth > touching || plane.overHole(x))
            continue;
        if (depth < 0.0f)
            collision_detail::snapOnto(plane, x);
        // How hard the wall presses: the speed the sweeps drove the grain into it, and once a step
        // the weight's share where the swarm's own collision with the room took it away before the
        // sweeps (a grain that still arrives with it is pushed for it below: not twice).
        const float vn = glm::dot(plane.normal, v);
        if (first)
            wall.push += std::max(rule.restingSpeed * std::max(plane.normal.y, 0.0f) + std::min(vn, 0.0f), 0.0f);
        if (vn < 0.0f) {
            v -= vn * plane.normal;
            wall.push -= vn;
        }
        if (!(rule.friction > 0.0f))
            continue;
        // The push over the step's sweeps so far bounds what friction has taken in all, from the
        // sliding speed and from the slip since the grain came to the wall.
        const Vec slide = v - glm::dot(plane.normal, v) * plane.normal;
        const float speed = glm::length(slide), most = rule.friction * wall.push - wall.slowed;
        if (speed > 0.0f && most > 0.0f) {
            v -= (std::min(speed, most) / speed) * slide;
            wall.slowed += std::min(speed, most);
        }
        wall.touched = true;
        if (const float hold = rule.friction * wall.push * rule.dt - wall.held; hold > 0.0f) {
            const Vec slip = wall.anchor + x;
            const Vec along = slip - glm::dot(slip, plane.normal) * plane.normal;
            x -= takenBack(along, hold, wall.held, float(kMostSlip) * 2.0f * rule.radius);
        }
    }
}

struct Box {
    Vec lo{std::numeric_limits<float>::max()}, hi{std::numeric_limits<float>::lowest()};
};

Box boundsOf(const Swarm& swarm)
{
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, swarm.size(), kGrainBlock), Box{},
        [&](const tbb::blocked_range<std::size_t>& r, Box box) {
            for (std::size_t i = r.begin(); i < r.end(); ++i) {
                box.lo = glm::min(box.lo, swarm.position(i));
                box.hi = glm::max(box.hi, swarm.position(i));
            }
            return box;
        },
        [](const Box& a, const Box& b) { return Box{glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)}; });
}

} // namespace

std::size_t GrainContacts::pairCount() const
{
    std::size_t count = 0;
    for (const auto& slab : m_pairs)
        count += slab.size();
    return count;
}

Vec3<std::int64_t> GrainContacts::cellOf(const Vec& x) const
{
    return Vec3<std::int64_t>(glm::floor(x / m_grid.spacing));
}

std::size_t GrainContacts::keyOf(const Vec3<std::int64_t>& cell) const
{
    if (!m_grid.hashed) {
        // Within the box (only a grain with a non-finite position could lie outside it).
        const Vec3<std::int64_t> c = glm::clamp(cell - m_grid.lo, Vec3<std::int64_t>(0), m_grid.dims - std::int64_t(1));
        return std::size_t((c.x * m_grid.dims.y + c.y) * m_grid.dims.z + c.z);
    }
    // Large odd multipliers spread neighbouring cells over the table; XOR mixes the three.
    const std::uint64_t h = std::uint64_t(cell.x) * 92837111u ^ std::uint64_t(cell.y) * 689287499u ^
                            std::uint64_t(cell.z) * 283923481u;
    return std::size_t(h % m_grid.cells);
}

void GrainContacts::plan(float spacing)
{
    // Numbered cells while the box holds at most a few per grain; a hash table of twice as many
    // buckets as grains beyond that (a swarm spread over a large space), in one slab.
    const std::size_t n = m_x.size();
    m_grid.spacing = spacing;
    m_grid.slabWidth = 1;
    const auto fits = [&](std::int64_t d) { return d > 0 && d < (std::int64_t(1) << 20); };
    const Vec3<std::int64_t> dims = m_grid.dims;
    if (fits(dims.x) && fits(dims.y) && fits(dims.z) &&
        std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z) <= 4 * n + 4096) {
        m_grid.hashed = false;
        m_grid.cells = std::size_t(dims.x * dims.y * dims.z);
    } else {
        m_grid.hashed = true;
        m_grid.cells = 2 * n;
    }
}

void GrainContacts::sortByCell(const Swarm& swarm, const GrainMemory& memory)
{
    const std::size_t n = swarm.size();
    const Box box = boundsOf(swarm);
    m_grid.lo = Vec3<std::int64_t>(glm::floor(box.lo / m_reach));
    m_grid.dims = Vec3<std::int64_t>(glm::floor(box.hi / m_reach)) - m_grid.lo + std::int64_t(1);
    m_x.resize(n);
    m_v.resize(n);
    plan(m_reach);
    // The last step's order (the swarm's on a first step), sorted anew by cell: each grain's place
    // in it, unless it moved more than a reach since (a grain that had no place has no pairs to
    // remember either).
    const bool known = memory.order.size() == n;
    const auto last = [&](std::size_t j) { return known ? memory.order[j] : std::uint32_t(j); };
    m_key.resize(n);
    m_from.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrainBlock), [&](const auto& r) {
        for (std::size_t j = r.begin(); j < r.end(); ++j) {
            const Vec x = swarm.position(last(j));
            m_key[j] = std::uint32_t(keyOf(cellOf(x)));
            // (m_from is free until the sort fills it: here, whether grain j keeps its place.)
            m_from[j] = known && glm::length(x - memory.end[j]) <= m_reach ? std::uint32_t(j) : kNew;
        }
    });
    // A counting sort, stable: a cell's grains in the last step's order.
    m_cellStart.assign(m_grid.cells + 1, 0);
    for (std::size_t j = 0; j < n; ++j)
        ++m_cellStart[m_key[j] + 1];
    for (std::size_t c = 0; c < m_grid.cells; ++c)
        m_cellStart[c + 1] += m_cellStart[c];
    m_order.resize(n);
    m_previous.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
        const std::uint32_t s = m_cellStart[m_key[j]]++;
        m_order[s] = last(j);
        m_previous[s] = m_from[j];
    }
    std::swap(m_from, m_previous);
    // Each cell's counter now stands at the next cell's start: shift them back.
    std::copy_backward(m_cellStart.begin(), m_cellStart.end() - 1, m_cellStart.end());
    m_cellStart[0] = 0;
    const std::size_t slabs =
        m_grid.hashed ? 1 : std::size_t((m_grid.dims.x + m_grid.slabWidth - 1) / m_grid.slabWidth);
    const std::size_t slabCells = m_grid.hashed ? 0 : std::size_t(m_grid.slabWidth * m_grid.dims.y * m_grid.dims.z);
    m_slabStart.resize(slabs + 1);
    for (std::size_t k = 0; k < slabs; ++k)
        m_slabStart[k] = m_cellStart[k * slabCells];
    m_slabStart[slabs] = n;
}

void GrainContacts::gather(const Swarm& swarm, std::span<const PlaneT<float>> room, const GrainMemory& memory)
{
    const std::size_t n = m_x.size();
    m_nearWall.resize(n);
    m_walls.resize(n);
    const bool known = memory.wallSlip.size() == n;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrainBlock), [&](const auto& r) {
        for (std::size_t s = r.begin(); s < r.end(); ++s) {
            m_x[s] = swarm.position(m_order[s]);
            m_v[s] = swarm.velocity(m_order[s]);
            // The walls the sweeps may bring it to: those within a few reaches (the sweeps move a
            // grain by its overlaps, each less than a reach); a room of over 32 planes, whose
            // further planes every grain visits, flags every grain.
            m_nearWall[s] = wallsWithin(room, m_x[s], 4.0f * m_reach) | (room.size() > kWallBits ? 1u : 0u);
            if (m_nearWall[s]) {
                const std::uint32_t j = m_from[s];
                m_walls[s] = GrainWall{};
                m_walls[s].anchor = known && j != kNew ? memory.wallSlip[j] - memory.end[j] : -m_x[s];
            }
        }
    });
}

void GrainContacts::findPairs(std::size_t slab)
{
    auto& pairs = m_pairs[slab];
    pairs.clear();
    const float reach2 = float(kBallsTouching) * float(kBallsTouching) * m_reach * m_reach;
    const auto near = [&](std::size_t s, std::size_t from, std::size_t to) {
        for (std::size_t t = std::max(from, s + 1); t < to; ++t) {
            const Vec d = m_x[t] - m_x[s];
            if (glm::dot(d, d) < reach2)
                pairs.push_back({std::uint32_t(s), std::uint32_t(t), newContact(d)});
        }
    };
    if (!m_grid.hashed) {
        // Numbered cells: only the 14 at or after a grain's own hold grains after it, in five
        // runs of cells adjacent along z (x-major numbering).
        const Vec3<std::int64_t> dims = m_grid.dims;
        for (std::size_t s = m_slabStart[slab]; s < m_slabStart[slab + 1]; ++s) {
            const Vec3<std::int64_t> c = glm::clamp(cellOf(m_x[s]) - m_grid.lo, Vec3<std::int64_t>(0),
                                                    dims - std::int64_t(1));
            const auto run = [&](std::int64_t x, std::int64_t y, std::int64_t z0, std::int64_t z1) {
                if (x >= dims.x || y < 0 || y >= dims.y)
                    return;
                const std::int64_t row = (x * dims.y + y) * dims.z;
                near(s, m_cellStart[std::size_t(row + std::max<std::int64_t>(z0, 0))],
                     m_cellStart[std::size_t(row + std::min(z1, dims.z - 1) + 1)]);
            };
            run(c.x, c.y, c.z, c.z + 1);
            run(c.x, c.y + 1, c.z - 1, c.z + 1);
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                run(c.x + 1, c.y + dy, c.z - 1, c.z + 1);
        }
        return;
    }
    std::array<std::size_t, 27> keys{};
    for (std::size_t s = m_slabStart[slab]; s < m_slabStart[slab + 1]; ++s) {
        const Vec3<std::int64_t> c = cellOf(m_x[s]);
        std::size_t count = 0;
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dz = -1; dz <= 1; ++dz) {
                    const Vec3<std::int64_t> d = c + Vec3<std::int64_t>(dx, dy, dz);
                    keys[count++] = keyOf(d);
                }
        // Two of the 27 cells may share a bucket: each once.
        std::sort(keys.begin(), keys.begin() + count);
        count = std::size_t(std::unique(keys.begin(), keys.begin() + count) - keys.begin());
        for (std::size_t k = 0; k < count; ++k)
            near(s, m_cellStart[keys[k]], m_cellStart[keys[k] + 1]);
    }
}

template <class F>
void GrainContacts::forEachPairInColours(F&& fn)
{
    const std::size_t slabs = m_pairs.size();
    for (std::size_t colour = 0; colour < 2; ++colour) {
        const std::size_t count = (slabs + 1 - colour) / 2;
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1), [&](const auto& r) {
            for (std::size_t m = r.begin(); m < r.end(); ++m)
                for (GrainPair& pair : m_pairs[2 * m + colour])
                    fn(pair);
        });
    }
}

void GrainContacts::sweep(std::span<const PlaneT<float>> room, const GrainRule& rule, bool first)
{
    // Equal grains: each takes half of a pair's relative move and speed change.
    const BallPairRule<float> pairRule{m_reach, 0.5f, 0.5f, rule.cor, rule.friction, rule.restingSpeed, rule.dt};
    forEachPairInColours([&](GrainPair& p) __attribute__((always_inline)) {
        touchBalls(m_x[p.a], m_v[p.a], m_x[p.b], m_v[p.b], p.contact, pairRule, first);
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m_x.size(), kGrainBlock), [&](const auto& r) {
        for (std::size_t s = r.begin(); s < r.end(); ++s)
            if (m_nearWall[s])
                keepInRoom(room, m_nearWall[s], rule, first, m_x[s], m_v[s], m_walls[s]);
    });
}

void GrainContacts::warmStart(const GrainMemory& memory)
{
    if (memory.row.empty())
        return;
    forEachPairInColours([&](GrainPair& p) {
        const std::uint32_t ja = m_from[p.a], jb = m_from[p.b];
        if (ja == kNew || jb == kNew)
            return;
        // Listed under the grain that came first in the last step's order; its sliding change
        // turns round with the pair's order.
        const std::uint32_t first = std::min(ja, jb), second = std::max(ja, jb);
        for (std::uint32_t k = memory.row[first]; k < memory.row[first + 1]; ++k) {
            const RememberedPair& old = memory.pairs[k];
            if (old.b != second)
                continue;
            const Vec d = m_x[p.b] - m_x[p.a];
            const float distance = glm::length(d);
            if (!(distance > 0.0f))
                return;
            const Vec n = d / distance;
            const Vec tangent = ja < jb ? old.tangent : -old.tangent;
            p.contact.anchor = (ja < jb ? old.slip : -old.slip) - (memory.end[jb] - memory.end[ja]);
            p.contact.normal = old.normal;
            p.contact.tangent = tangent - glm::dot(tangent, n) * n;
            const Vec change = p.contact.normal * n + p.contact.tangent;
            m_v[p.a] -= 0.5f * change;
            m_v[p.b] += 0.5f * change;
            return;
        }
    });
}

void GrainContacts::remember(GrainMemory& memory) const
{
    const std::size_t n = m_x.size();
    memory.order = m_order;
    memory.end = m_x;
    memory.wallSlip.resize(n);
    for (std::size_t s = 0; s < n; ++s) {
        const bool touched = m_nearWall[s] != 0 && m_walls[s].touched;
        memory.wallSlip[s] = touched ? rememberedSlip(m_walls[s].anchor + m_x[s], m_reach) : Vec(0.0f);
    }
    std::vector<std::size_t> base(m_pairs.size() + 1, 0);
    for (std::size_t k = 0; k < m_pairs.size(); ++k)
        base[k + 1] = base[k] + m_pairs[k].size();
    memory.pairs.resize(base.back());
    memory.row.assign(n + 1, 0);
    // A slab's pairs are listed by their first grain, and the slabs hold disjoint runs of grains.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m_pairs.size(), 1), [&](const auto& r) {
        for (std::size_t k = r.begin(); k < r.end(); ++k)
            for (std::size_t q = 0; q < m_pairs[k].size(); ++q) {
                const GrainPair& p = m_pairs[k][q];
                const Vec d = m_x[p.b] - m_x[p.a];
                const Vec u = d / std::max(glm::length(d), std::numeric_limits<float>::min());
                Vec slip = p.contact.anchor + d;
                slip = rememberedSlip(Vec(slip - glm::dot(slip, u) * u), m_reach);
                memory.pairs[base[k] + q] = RememberedPair{p.b, p.contact.normal, p.contact.tangent, slip};
                ++memory.row[p.a + 1];
            }
    });
    for (std::size_t j = 0; j < n; ++j)
        memory.row[j + 1] += memory.row[j];
}

void GrainContacts::solve(Swarm& swarm, std::size_t slot, std::span<const PlaneT<float>> room, const GrainRule& rule,
                          int sweeps)
{
    const std::size_t n = swarm.size();
    if (m_memory.size() <= slot)
        m_memory.resize(slot + 1);
    GrainMemory& memory = m_memory[slot];
    m_reach = 2.0f * rule.radius;
    if (n < 2 || !(m_reach > 0.0f)) {
        m_pairs.clear();
        memory = GrainMemory{};
        return;
    }
    sortByCell(swarm, memory);
    gather(swarm, room, memory);
    m_pairs.resize(m_slabStart.size() - 1);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m_pairs.size(), 1), [&](const auto& r) {
        for (std::size_t k = r.begin(); k < r.end(); ++k)
            findPairs(k);
    });
    warmStart(memory);
    for (int k = 0; k < sweeps; ++k)
        sweep(room, rule, k == 0);
    remember(memory);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrainBlock), [&](const auto& r) {
        for (std::size_t s = r.begin(); s < r.end(); ++s)
            swarm.set(m_order[s], m_x[s], m_v[s]);
    });
}

} // namespace pba::detail
