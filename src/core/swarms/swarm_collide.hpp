#pragma once
// Phases 2 and 3 of a swarm's step: which particles of a block are near a surface, and the
// collision rule for them (the exact response's redone step; reflect and clamp's pass in a
// World's room, over the whole block or over a batch gathered from several). Private to
// src/core/swarms/swarm.cpp (see swarm_block.hpp).
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <type_traits>

#include "pba/detail/swarm_kernel.hpp"
#include "pba/swarm.hpp"
#include "surfaces/room_surfaces.hpp"
#include "surfaces/surface_tests.hpp"
#include "swarms/swarm_block.hpp"

namespace pba {

// Internal linkage, as when this lived in swarm.cpp: the one file that includes it.
namespace {

/// Whether n states are all finite: one pass over the six arrays with one accumulator (six
/// separate reductions measured slower), for the blocks whose states a loop without the test
/// wrote (the exact response's).
bool allFinite(const Arrays& a, std::size_t b, std::size_t n)
{
    const float* __restrict arrays[6] = {a.px + b, a.py + b, a.pz + b, a.vx + b, a.vy + b, a.vz + b};
    std::uint32_t exponent = 0;
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k)
        for (const float* values : arrays)
            exponent = std::max(exponent, exponentField(values[k]));
    return exponent != kSpecialExponent;
}

/// Phase 2 of a block: which particles need a collision rule, marked in `hit`; returns how many
/// (none in most blocks of a swarm in flight). For reflect and clamp, those that ended the step
/// within a surface's contact tolerance (or beyond it): their rules look at where the step
/// ended. The exact response also redoes the steps that started there; whether a particle
/// started clear is remembered from its last step (`remember`), so only the ends are tested
/// here. `coversAll`: a particle clear of the box's walls is clear of every plane
/// (boxCoversAll), so they are the whole test, and no margins are needed. A pass of its own over
/// the block in L1: done in the integration loop, on the positions still in registers, its
/// fifteen instructions a vector more cost the loop, which is bound by its instructions, more
/// than this pass does (docs/performance.md).
std::size_t classifyBlock(const Arrays& a, std::size_t begin, std::size_t n, std::span<const PlaneT<float>> planes,
                          const std::optional<BoxWallsT<float>>& box, bool coversAll, bool remember,
                          std::uint8_t* __restrict hit)
{
    const float *x = a.px + begin, *y = a.py + begin, *z = a.pz + begin;
    if (!remember && coversAll)
        return markUnclearInBox(ClearRegionT<float>(*box), x, y, z, n, hit);
    alignas(64) float margin[kBlock];
    if (box)
        setClearanceInBox(*box, x, y, z, n, margin);
    else
        std::fill_n(margin, n, std::numeric_limits<float>::infinity());
    const std::uint64_t done = box ? box->mask : 0;
    for (std::size_t p = 0; p < planes.size(); ++p)
        if (p >= 64 || (done >> p & 1u) == 0)
            lowerClearance(planes[p], x, y, z, n, margin);
    std::uint32_t count = 0;
    if (!remember) {
        // vectorised: checked
        for (std::size_t k = 0; k < n; ++k) {
            hit[k] = static_cast<std::uint8_t>(!(margin[k] > 0.0f));
            count += hit[k];
        }
        return count;
    }
    std::uint8_t* __restrict clear = a.clear + begin;
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k) {
        const std::uint8_t clearNow = margin[k] > 0.0f;
        hit[k] = static_cast<std::uint8_t>((clearNow & clear[k]) ^ 1u);
        clear[k] = clearNow;
        count += hit[k];
    }
    return count;
}

/// Phase 3 of a block, exact response: the particles that met a surface redo their step with
/// the rule a Particle uses (time of impact on the integrator's own path, from the start
/// state). Kept out of line: it is scalar, so it need not be copied for every instruction set.
template <Integrator kIntegrator>
[[gnu::noinline]] std::uint64_t collideExactly(const Arrays& a, std::size_t begin, std::size_t n,
                                               const SwarmKernelFields& fields, float restitution,
                                               float friction, float dt, std::span<const PlaneT<float>> planes,
                                               const float (*start)[kBlock], const std::uint8_t* hit)
{
    auto accel = [&](const Vec3<float>& x, const Vec3<float>& v) {
        return swarmAccelerationAll(fields, x, v);
    };
    std::uint64_t bounces = 0;
    for (std::size_t k = 0; k < n; ++k) {
        if (!hit[k])
            continue;
        const std::size_t i = begin + k;
        Vec3<float> x(start[0][k], start[1][k], start[2][k]);
        Vec3<float> v(start[3][k], start[4][k], start[5][k]);
        bounces += stepExact(kIntegrator, planes, restitution, x, v, dt, accel, friction);
        a.px[i] = x.x, a.py[i] = x.y, a.pz[i] = x.z;
        a.vx[i] = v.x, a.vy[i] = v.y, a.vz[i] = v.z;
        a.clear[i] = static_cast<std::uint8_t>(clearOfAll(planes, x));
    }
    return bounces;
}

/// What a collision pass over some particles reports: its bounces, how many it left to the
/// whole rule, and whether every state it wrote is finite.
struct PassResult {
    int bounces = 0;
    std::uint32_t unfinished = 0;
    bool finite = true;
};

/// The reflect or clamp rule over the n particles of a block, or of a batch gathered from
/// several, that met a surface of a World's room, in one loop of selects: the floor and its
/// hole (RoomSurfacesT::commonPass), and whether the result is finite. A particle that pass
/// cannot finish (needsWholeRule: at the ceiling, a wall or the grille, at a corner, at the
/// shaft's wall) is left as the integrator left it and marked in `unfinished` for a Particle's
/// whole rule (wholeRule). A particle clear of every surface is left exactly as it was. With
/// `kFriction` a particle the floor pushed rubs along it (rubbedByPush, as a Particle's rule
/// and the whole rule do), which reads and writes its velocity's x and z as well.
///
/// One loop where there were four (which planes were crossed, a pass a plane, which particles
/// were still outside, the fold), faster at rest with the same states. The shaft's
/// wall is left to the whole rule: the dryer blows particles out of the shaft within a tenth of
/// a second, a few hundred a step of a million, and its square root and two divisions in this
/// loop for every particle cost more than a tenth of the step (docs/performance.md).
template <bool kHole, bool kFriction>
PassResult passInRoom(const float* __restrict px, float* __restrict py, const float* __restrict pz,
                      float* __restrict vx, float* __restrict vy, float* __restrict vz, const float* __restrict s0,
                      const float* __restrict s1, const float* __restrict s2, std::uint32_t* __restrict unfinished,
                      std::size_t n, const RoomSurfacesT<float> room, float restitution, float back, float friction)
{
    int bounces = 0;
    std::uint32_t count = 0, exponent = 0; // 32 bits, as wide as a float: 16 particles a vector
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k) {
        // The floor moves a particle along y only, so only y and v.y are written (and v's other
        // components not even read): the other four stay as the integration wrote and checked
        // them. Storing all six again made six stores a particle where two do.
        const Vec3<float> x(px[k], py[k], pz[k]);
        const Vec3<float> v(0.0f, vy[k], 0.0f);
        const Vec3<float> start(s0[k], s1[k], s2[k]);
        Vec3<float> passedX = x, passedV = v;
        int bounced = 0;
        room.template commonPass<kHole>(restitution, back, start, passedX, passedV, bounced);
        const bool whole = room.needsWholeRule(passedX);
        unfinished[k] = static_cast<std::uint32_t>(whole);
        count += static_cast<std::uint32_t>(whole);
        bounces += whole ? 0 : bounced;
        const float y = whole ? x.y : passedX.y, velocityY = whole ? v.y : passedV.y;
        exponent = std::max(exponent, exponentField(y + velocityY));
        py[k] = y, vy[k] = velocityY;
        if constexpr (kFriction) { // the floor changed v.y alone; the rub leaves it as it is
            const Vec3<float> after = rubbedByPush(Vec3<float>(vx[k], passedV.y, vz[k]),
                                                   Vec3<float>(0.0f, passedV.y - v.y, 0.0f), friction);
            vx[k] = whole ? vx[k] : after.x, vz[k] = whole ? vz[k] : after.z;
        }
    }
    return PassResult{bounces, count, exponent != kSpecialExponent};
}

/// The first index from k on, below n, whose flag in `which` is set; n if there is none. Sixteen
/// flags at a time: a collision pass at rest marks one particle in a block or none, and a
/// branch on each of the block's 512 flags was most of the whole rule's time.
std::size_t nextMarked(const std::uint32_t* which, std::size_t k, std::size_t n)
{
    for (; k + 16 <= n; k += 16) {
        std::uint32_t any = 0;
        for (std::size_t j = 0; j < 16; ++j)
            any |= which[k + j];
        if (any != 0)
            break;
    }
    while (k < n && which[k] == 0)
        ++k;
    return k;
}

/// A Particle's whole rule, from where the integrator left them, for the `marked` particles
/// flagged in `which` (all n of them with nullptr) among n of `a` from b. In a World's room its
/// first pass is the room's (RoomSurfacesT::firstPass: the same functions over the same planes
/// in the same order), the rest only for a particle still outside; among other planes it is the
/// rule as a Particle runs it, which first tests whether the particle is inside every plane.
/// With `friction`, each particle then rubs along the push its rule gave it, as a Particle's does
/// (rubbedByPush). Out of line and scalar, as collideExactly. Returns the bounces; clears `finite` if a
/// state it wrote is not.
[[gnu::noinline]] std::uint64_t wholeRule(const Arrays& a, std::size_t b, std::size_t n, float restitution,
                                          std::span<const PlaneT<float>> planes, CollisionResponse response,
                                          const std::optional<RoomSurfacesT<float>>& room,
                                          const StartPositions& start, const std::uint32_t* which,
                                          std::size_t marked, bool& finite, float friction)
{
    const bool reflect = response == CollisionResponse::Reflect;
    std::uint64_t bounces = 0;
    const auto next = [&](std::size_t k) { return which ? nextMarked(which, k, n) : k; };
    for (std::size_t k = next(0), left = marked; k < n && left > 0; k = next(k + 1), --left) {
        const std::size_t i = b + k;
        const Vec3<float> from(start[0][k], start[1][k], start[2][k]);
        const Vec3<float> x0(a.px[i], a.py[i], a.pz[i]), v0(a.vx[i], a.vy[i], a.vz[i]);
        Vec3<float> x = x0, v = v0;
        int bounced = 0;
        if (room) {
            if (room->hasHole())
                room->firstPass<true>(restitution, reflect ? 2.0f : 1.0f, from, x, v, bounced);
            else
                room->firstPass<false>(restitution, reflect ? 2.0f : 1.0f, from, x, v, bounced);
            if (room->needsWholeRule(x))
                bounced += reflect ? reflectAfterStep(planes, restitution, from, x, v, 1)
                                   : clampAfterStep(planes, restitution, from, x, v, 1);
        } else {
            bounced = reflect ? reflectAfterStep(planes, restitution, from, x, v)
                              : clampAfterStep(planes, restitution, from, x, v);
        }
        if (bounced == 0 && x == x0 && v == v0)
            continue;
        if (friction > 0.0f)
            v = rubbedByPush(v, v - v0, friction);
        bounces += static_cast<std::uint64_t>(bounced);
        a.px[i] = x.x, a.py[i] = x.y, a.pz[i] = x.z;
        a.vx[i] = v.x, a.vy[i] = v.y, a.vz[i] = v.z;
        finite = finite && exponentOfSum(x, v) != kSpecialExponent;
    }
    return bounces;
}

/// The reflect or clamp rule for n particles of `a` from b that met a surface (a block, or a
/// batch gathered from several), from their start positions: passInRoom and the whole rule for
/// what it leaves in a World's room, the whole rule for each particle among other planes (a
/// plane at an angle: no scene has one, Swarm::step takes any). Compiled once for each
/// instruction set, apart from the integration loops that call it: the collision code does not
/// depend on the integrator, and inlined into each integrator's loop it was compiled four times
/// over. Returns the bounces; clears `finite` if a state it wrote is not; sets `moved` to how
/// many particles the pass bounced or left to the whole rule (all n among other planes): what
/// keeps a block crowded, a hint that changes no result (from the pass's counts: counting the
/// particles it moved, four instructions a vector more, was slower at rest).
PBA_FOR_EACH_INSTRUCTION_SET
std::uint64_t collideHits(const Arrays& a, std::size_t b, std::size_t n, float restitution, float friction,
                          std::span<const PlaneT<float>> planes, CollisionResponse response,
                          const std::optional<RoomSurfacesT<float>>& room, const StartPositions& start, bool& finite,
                          std::size_t& moved)
{
    moved = n;
    if (!room)
        return wholeRule(a, b, n, restitution, planes, response, room, start, nullptr, n, finite, friction);
    alignas(64) std::uint32_t unfinished[kBlock];
    const float back = response == CollisionResponse::Reflect ? 2.0f : 1.0f; // see pushBack
    const auto pass = [&](auto hole, auto rub) {
        return passInRoom<decltype(hole)::value, decltype(rub)::value>(
            a.px + b, a.py + b, a.pz + b, a.vx + b, a.vy + b, a.vz + b, start[0], start[1], start[2], unfinished, n,
            *room, restitution, back, friction);
    };
    const auto withHole = [&](auto rub) {
        return room->hasHole() ? pass(std::true_type{}, rub) : pass(std::false_type{}, rub);
    };
    const PassResult result = friction > 0.0f ? withHole(std::true_type{}) : withHole(std::false_type{});
    finite = finite && result.finite;
    moved = static_cast<std::size_t>(result.bounces) + result.unfinished;
    std::uint64_t bounces = static_cast<std::uint64_t>(result.bounces);
    if (result.unfinished > 0)
        bounces += wholeRule(a, b, n, restitution, planes, response, room, start, unfinished, result.unfinished,
                             finite, friction);
    return bounces;
}

/// Phase 3, reflect and clamp, for the blocks where few particles met a surface (where rain
/// lands: a handful of the 512): collideHits over just those particles, gathered from
/// several blocks into a batch of their own and scattered back. Over one block's handful,
/// padded to a vector, the rule's pass costs as much as listing and gathering them; over the
/// whole block it cost a sixth of the landed phase's step (docs/performance.md). A
/// particle clear of every surface is left exactly as it was by every part of the rule, and
/// the rule treats each particle by itself, so the result is the same bit for bit (tested). The
/// batch is filled up to whole vectors with copies of one such particle, so its loops have no
/// scalar remainder.
class GatheredHits {
public:
    static constexpr std::size_t kCapacity = 2 * kGatherMax;
    static_assert(kCapacity % kGatherWidth == 0, "a full batch is whole vectors: its padding fits");

    GatheredHits(const Arrays& a, float restitution, float friction, std::span<const PlaneT<float>> planes,
                 CollisionResponse response, const std::optional<RoomSurfacesT<float>>& room)
        : m_a(a), m_restitution(restitution), m_friction(friction), m_planes(planes), m_response(response),
          m_room(room)
    {
    }

    /// Adds the particles of block b marked in `hit` (at most kGatherMax, and fewer than n), with
    /// their start positions; runs the batch first if they would not fit. Returns its bounces.
    std::uint64_t add(std::size_t b, std::size_t n, std::uint8_t* hit, const float (*start)[kBlock])
    {
        std::array<std::uint16_t, kGatherMax> index;
        std::size_t spare = 0;
        const std::size_t m = listHits(hit, n, index.data(), spare);
        const std::uint64_t bounces = m_count + m > kCapacity ? collide() : 0;
        const float* const arrays[6] = {m_a.px + b, m_a.py + b, m_a.pz + b, m_a.vx + b, m_a.vy + b, m_a.vz + b};
        if (!m_haveSpare) {
            for (std::size_t c = 0; c < 6; ++c)
                m_spare[c] = arrays[c][spare];
            for (std::size_t c = 0; c < 3; ++c)
                m_spare[6 + c] = start[c][spare];
            m_haveSpare = true;
        }
        for (std::size_t j = 0; j < m; ++j) {
            const std::size_t k = index[j];
            m_index[m_count + j] = b + k;
            for (std::size_t c = 0; c < 6; ++c)
                m_state[c][m_count + j] = arrays[c][k];
            for (std::size_t c = 0; c < 3; ++c)
                m_from[c][m_count + j] = start[c][k];
        }
        m_count += m;
        return bounces;
    }

    /// Runs the rule over the particles gathered so far and writes them back. Returns the bounces.
    std::uint64_t collide()
    {
        if (m_count == 0)
            return 0;
        const std::size_t width = (m_count + kGatherWidth - 1) / kGatherWidth * kGatherWidth;
        for (std::size_t j = m_count; j < width; ++j) {
            for (std::size_t c = 0; c < 6; ++c)
                m_state[c][j] = m_spare[c];
            for (std::size_t c = 0; c < 3; ++c)
                m_from[c][j] = m_spare[6 + c];
        }
        const Arrays gathered{m_state[0], m_state[1], m_state[2], m_state[3], m_state[4], m_state[5],
                              nullptr,    nullptr,    nullptr,    nullptr};
        // The states the rule wrote are checked by it; the others were checked with their block.
        bool finite = true;
        std::size_t moved = 0;
        const std::uint64_t bounces = collideHits(gathered, 0, width, m_restitution, m_friction, m_planes, m_response,
                                                  m_room,
                                                  {m_from[0], m_from[1], m_from[2]}, finite, moved);
        float* const arrays[6] = {m_a.px, m_a.py, m_a.pz, m_a.vx, m_a.vy, m_a.vz};
        for (std::size_t j = 0; j < m_count; ++j) {
            for (std::size_t c = 0; c < 6; ++c)
                arrays[c][m_index[j]] = m_state[c][j];
            if (!finite) // its block's flag was set before its collision was resolved here
                m_a.finite[m_index[j] / kBlock] = 0;
        }
        m_count = 0;
        return bounces;
    }

private:
    const Arrays& m_a;
    float m_restitution, m_friction;
    std::span<const PlaneT<float>> m_planes;
    CollisionResponse m_response;
    const std::optional<RoomSurfacesT<float>>& m_room;
    std::size_t m_count = 0;
    bool m_haveSpare = false;
    std::array<float, 9> m_spare{}; ///< a clear particle's state and start: the padding
    std::array<std::size_t, kCapacity> m_index;
    alignas(64) float m_state[6][kCapacity];
    alignas(64) float m_from[3][kCapacity];
};

} // namespace

} // namespace pba
