#include "pba/swarm.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <atomic>
#include <cstring>
#include <limits>
#include <optional>
#include <type_traits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <x86intrin.h>
#endif

#include "room_surfaces.hpp"
#include "surface_tests.hpp"

namespace pba {

namespace {

/// splitmix64: a counter-based generator, so particle i's values depend on (seed, i) alone.
std::uint64_t mix(std::uint64_t z)
{
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

double uniform(std::uint64_t seed, std::uint64_t i, int component)
{
    return double(mix(mix(seed) ^ mix(i * 8 + std::uint64_t(component))) >> 11) * 0x1.0p-53;
}

/// Whether a point clear of the box's walls is clear of every plane: the other planes (the
/// grille at the bottom of the hole's shaft) are clear of the whole of the box's clear region,
/// tested at its eight corners, in double precision.
bool boxCoversAll(const BoxWallsT<float>& box, std::span<const PlaneT<float>> planes)
{
    for (std::size_t p = 0; p < planes.size(); ++p) {
        if (p < 64 && (box.mask >> p & 1u) != 0)
            continue;
        const PlaneT<float>& plane = planes[p];
        for (int corner = 0; corner < 8; ++corner) {
            const double x = corner & 1 ? box.clearHi[0] : box.clearLo[0];
            const double y = corner & 2 ? box.clearHi[1] : box.clearLo[1];
            const double z = corner & 4 ? box.clearHi[2] : box.clearLo[2];
            const double d = double(plane.normal.x) * x + double(plane.normal.y) * y + double(plane.normal.z) * z -
                             double(plane.offset);
            if (!(d > 2.0 * double(collision_detail::contactTolerance(plane))))
                return false;
        }
    }
    return true;
}

/// The same surfaces: what the exact response's remembered flags were computed against.
bool samePlanes(std::span<const PlaneT<float>> a, std::span<const PlaneT<float>> b)
{
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& p, const auto& q) {
        return p.normal == q.normal && p.offset == q.offset && p.holeRadius == q.holeRadius &&
               p.holeCentre == q.holeCentre;
    });
}

// A function compiled once for each instruction set (see stepSwarmRange). GCC on x86-64 only:
// clang 14 does not combine target_clones with flatten, and other CPUs have other instruction
// sets (there the loop is compiled once, for the build's target).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PBA_FOR_EACH_INSTRUCTION_SET [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"), gnu::flatten]]
#else
#define PBA_FOR_EACH_INSTRUCTION_SET
#endif

/// Particles a block: the start states of one block stay in L1 while the block is stepped.
constexpr std::size_t kBlock = 512;
/// The block's start states are six rows of this many floats: 192 bytes more than a block, so
/// that element k of the six rows lies at six different offsets in a 4 KB page (see
/// Swarm::m_state for why that matters).
constexpr std::size_t kStartRow = kBlock + 48;
/// A block with at most this many particles at a surface has them gathered, with those of other
/// such blocks, for the collision rule (GatheredHits), padded to whole vectors of kGatherWidth
/// floats (AVX-512's 16).
constexpr std::size_t kGatherMax = 64;
constexpr std::size_t kGatherWidth = 16;
/// Below this many particles threads cost more than they save (measured: 3x slower at 1,000).
constexpr std::size_t kParallelThreshold = 32768;

template <Integrator kIntegrator, class Accel>
inline void integrateAs(Vec3<float>& x, Vec3<float>& v, float dt, Accel&& accel)
{
    if constexpr (kIntegrator == Integrator::ForwardEuler)
        forwardEuler(x, v, dt, accel);
    else if constexpr (kIntegrator == Integrator::SemiImplicitEuler)
        semiImplicitEuler(x, v, dt, accel);
    else if constexpr (kIntegrator == Integrator::VelocityVerlet)
        velocityVerlet(x, v, dt, accel);
    else
        rk4(x, v, dt, accel);
}

/// Where the steps of a block's particles began: three rows, x, y and z.
using StartPositions = std::array<const float*, 3>;

struct Arrays {
    float *px, *py, *pz, *vx, *vy, *vz;
    std::uint8_t* clear; ///< 1: the position is clear of every surface (known from the last step)
    std::uint8_t* finite; ///< per block: 1 when its six arrays are all finite after the step
    std::uint8_t* crowded; ///< per block: 1 when the collision pass moved most of it last step
    std::uint8_t* blowing; ///< per block: steps before the dryer's split is tried again (integrateInDryer)
    SwarmPhaseTimes* phases = nullptr; ///< where to add each phase's time, if anywhere
};

/// Adds the time since its last lap to a phase's total; does nothing without a SwarmPhaseTimes.
/// On x86-64 it reads the time-stamp counter, converted to nanoseconds with a rate measured
/// once against steady_clock: an instruction, where steady_clock::now() is a call, which
/// makes the compiler keep none of a loop's constants in vector registers across it (the
/// calling convention saves none of them). With steady_clock, four laps a block of 512 made a
/// timed step of blow-dryer-swarm at 1e6 14-18% slower than the untimed one in flight and 28-29%
/// at rest, and charged most of it to the short phases (the check, which stores a flag, 0.07-0.08
/// thread-ms a step); with the counter 4% and 6-15%, the check 0.023 (2026-11-26).
class PhaseClock {
public:
    explicit PhaseClock(SwarmPhaseTimes* times) : m_times(times)
    {
        if (m_times)
            m_last = now();
    }
    void lap(SwarmPhaseTimes::Phase phase)
    {
        if (!m_times)
            return;
        const std::uint64_t t = now();
        const std::uint64_t ticks = t > m_last ? t - m_last : 0; // cores' counters may differ a little
        const auto ns = static_cast<std::uint64_t>(static_cast<double>(ticks) * nanosecondsPerTick());
        m_times->nanoseconds[phase].fetch_add(ns, std::memory_order_relaxed);
        m_last = t;
    }

private:
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    static std::uint64_t now() { return __rdtsc(); }
    /// The counter's rate, from 5 ms of steady_clock (the counter runs at a constant rate on
    /// every x86-64 CPU of the last fifteen years, whatever the core's clock).
    static double nanosecondsPerTick()
    {
        static const double rate = [] {
            const auto t0 = std::chrono::steady_clock::now();
            const std::uint64_t c0 = __rdtsc();
            auto t1 = t0;
            while (t1 - t0 < std::chrono::milliseconds(5))
                t1 = std::chrono::steady_clock::now();
            const std::uint64_t c1 = __rdtsc();
            const double ns = std::chrono::duration<double, std::nano>(t1 - t0).count();
            return c1 > c0 ? ns / static_cast<double>(c1 - c0) : 0.0; // a counter that stood still: no times
        }();
        return rate;
    }
#else
    static std::uint64_t now()
    {
        return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                              std::chrono::steady_clock::now().time_since_epoch())
                                              .count());
    }
    static double nanosecondsPerTick() { return 1.0; }
#endif
    SwarmPhaseTimes* m_times;
    std::uint64_t m_last = 0;
};

/// The exponent field of f: all ones (kSpecialExponent) exactly when f is an infinity or a NaN.
/// A loop keeps the largest it sees, an unsigned maximum (one instruction a vector, where
/// comparing each and ORing the result into a flag took three; a float sum would not vectorise
/// without reassociation), and tests it once at the end.
constexpr std::uint32_t kSpecialExponent = 0x7f800000u;
inline std::uint32_t exponentField(float f)
{
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    return bits & kSpecialExponent;
}

/// The exponent field of the sum of the state's six components: special whenever a component
/// is; a finite state whose sum overflows only sends Swarm::findNonFinite to look for nothing.
inline std::uint32_t exponentOfSum(const Vec3<float>& x, const Vec3<float>& v)
{
    return exponentField(x.x + x.y + x.z + v.x + v.y + v.z);
}

/// The exponent field a loop that integrates keeps for the state it wrote: exponentOfSum's, but
/// for semi-implicit Euler the new position's three components alone. Its new position is
/// x + v dt with v the new velocity: a component of v that is infinite or NaN makes the same
/// component of the position infinite or NaN (an infinite product, or 0 times infinity, or a
/// NaN, plus anything finite or not), so the position's sum is special whenever any of the six
/// components is. Two additions a particle where the six's sum takes five, in the loop whose
/// instructions are what a step waits on.
template <Integrator kIntegrator>
inline std::uint32_t exponentOfStep(const Vec3<float>& x, const Vec3<float>& v)
{
    if constexpr (kIntegrator == Integrator::SemiImplicitEuler)
        return exponentField(x.x + x.y + x.z);
    else
        return exponentOfSum(x, v);
}

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

/// Phase 1 of a block: the plain integrator step for every particle, a loop with no branches
/// the vectoriser cannot turn into selects. The start states are kept for phase 2.
template <Integrator kIntegrator, bool kKeepStartVelocity, class Accel>
bool integrateBlock(float* __restrict px, float* __restrict py, float* __restrict pz, float* __restrict vx,
                    float* __restrict vy, float* __restrict vz, float* __restrict s0, float* __restrict s1,
                    float* __restrict s2, float* __restrict s3, float* __restrict s4, float* __restrict s5,
                    std::size_t n, float dt, Accel accel)
{
    // Distinct arrays (restrict) and an acceleration holding its fields by value: what lets
    // the compiler vectorise this loop without alias checks.
    std::uint32_t exponent = 0;
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k) {
        Vec3<float> x(px[k], py[k], pz[k]);
        Vec3<float> v(vx[k], vy[k], vz[k]);
        s0[k] = x.x, s1[k] = x.y, s2[k] = x.z;
        if constexpr (kKeepStartVelocity) // only the exact response redoes the step
            s3[k] = v.x, s4[k] = v.y, s5[k] = v.z;
        integrateAs<kIntegrator>(x, v, dt, accel);
        exponent = std::max(exponent, exponentOfStep<kIntegrator>(x, v));
        px[k] = x.x, py[k] = x.y, pz[k] = x.z;
        vx[k] = v.x, vy[k] = v.y, vz[k] = v.z;
    }
    return exponent != kSpecialExponent;
}

/// Phase 1 of a block away from the dryer: integrateBlock's loop with `away`, the acceleration
/// as it is where the dryer cannot push (withoutDryer's: no roots, no divisions), and one test
/// of whether any point the integrator evaluates it at may be one where it can
/// (blowDryerMayPushWithin). Those particles (`blown`, counted in `blownCount`) are left at
/// their start states for integrateGathered; every other one had the acceleration the whole one
/// would have given it at every point, so it took the same step.
template <Integrator kIntegrator, bool kKeepStartVelocity, DryerAxis kAxis, class Away>
bool integrateAwayBlock(float* __restrict px, float* __restrict py, float* __restrict pz, float* __restrict vx,
                        float* __restrict vy, float* __restrict vz, float* __restrict s0, float* __restrict s1,
                        float* __restrict s2, float* __restrict s3, float* __restrict s4, float* __restrict s5,
                        std::uint32_t* __restrict blown, std::size_t& blownCount, std::size_t n, float dt,
                        BlowDryerReach reach, Away away)
{
    std::uint32_t exponent = 0, count = 0;
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3<float> x0(px[k], py[k], pz[k]);
        const Vec3<float> v0(vx[k], vy[k], vz[k]);
        s0[k] = x0.x, s1[k] = x0.y, s2[k] = x0.z;
        if constexpr (kKeepStartVelocity)
            s3[k] = v0.x, s4[k] = v0.y, s5[k] = v0.z;
        Vec3<float> x = x0, v = v0;
        const bool pushed = blowDryerMayPushWithin<kAxis>(reach, x0, v0);
        integrateAs<kIntegrator>(x, v, dt, away);
        // Selects a component at a time (a select of whole vectors is a branch to GCC).
        for (int c = 0; c < 3; ++c)
            x[c] = pushed ? x0[c] : x[c], v[c] = pushed ? v0[c] : v[c];
        exponent = std::max(exponent, exponentOfSum(x, v));
        px[k] = x.x, py[k] = x.y, pz[k] = x.z;
        vx[k] = v.x, vy[k] = v.y, vz[k] = v.z;
        blown[k] = static_cast<std::uint32_t>(pushed);
        count += static_cast<std::uint32_t>(pushed);
    }
    blownCount = count;
    return exponent != kSpecialExponent;
}

/// Returns whether every state it wrote is finite.
template <Integrator kIntegrator, class Accel>
bool integrateBlock(const Arrays& a, std::size_t b, std::size_t n, float dt, float (*start)[kStartRow],
                    CollisionResponse response, Accel accel)
{
    if (response == CollisionResponse::Exact)
        return integrateBlock<kIntegrator, true>(a.px + b, a.py + b, a.pz + b, a.vx + b, a.vy + b, a.vz + b, start[0],
                                          start[1], start[2], start[3], start[4], start[5], n, dt, accel);
    else
        return integrateBlock<kIntegrator, false>(a.px + b, a.py + b, a.pz + b, a.vx + b, a.vy + b, a.vz + b, start[0],
                                           start[1], start[2], start[3], start[4], start[5], n, dt, accel);
}

/// Phase 2 of a block: which particles need a collision rule, marked in `hit`; returns how many
/// (none in most blocks of a swarm in flight). For reflect and clamp, those that ended the step
/// within a surface's contact tolerance (or beyond it): their rules look at where the step
/// ended. The exact response also redoes the steps that started there; whether a particle
/// started clear is remembered from its last step (`remember`), so only the ends are tested
/// here. `coversAll`: a particle clear of the box's walls is clear of every plane
/// (boxCoversAll), so they are the whole test, and no margins are needed. Done instead in the
/// integration loop, on the new positions while they are in registers (the same flags, words
/// written beside the states), it measured slower: blow-dryer-swarm from t = 2 s at 1e6 on 2
/// threads, integration 1.58-1.66 ms of thread time a step against 1.27 for this test's 0.28
/// (2026-11-26). The integration loop is bound by its instructions; its fifteen more cost
/// more than a pass of its own over the block in L1.
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
                                               float dt, std::span<const PlaneT<float>> planes,
                                               const float (*start)[kStartRow], const std::uint8_t* hit)
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
        bounces += stepExact(kIntegrator, planes, restitution, x, v, dt, accel);
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
/// whole rule (wholeRule). A particle clear of every surface is left exactly as it was.
///
/// It replaced, for the blocks and batches where particles meet a surface, four loops: which
/// planes some particle crossed (the block's bounds), a pass for each such plane (the floor's
/// with the shaft's wall: a square root and two divisions for every particle), which particles
/// were still outside, and the fold; with the finite check moved into the loops that write the
/// states, fountain-1m from t = 8 s (every block on the floor, every step) went from 718 to
/// 755-789 physics steps a second, the same states bit for bit. The shaft's wall is among the
/// rare cases: the dryer's push blows particles out of the shaft within a tenth of a second, and
/// 250 to 360 a step of a million take the whole rule; with the wall in this loop (its square
/// root and two divisions for every particle) the same measured 640-675.
template <bool kHole>
PassResult passInRoom(const float* __restrict px, float* __restrict py, const float* __restrict pz,
                      float* __restrict vy, const float* __restrict s0, const float* __restrict s1,
                      const float* __restrict s2, std::uint32_t* __restrict unfinished, std::size_t n,
                      const RoomSurfacesT<float> room, float restitution, float back)
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
    }
    return PassResult{bounces, count, exponent != kSpecialExponent};
}

/// The first index from k on, below n, whose flag in `which` is set; n if there is none. Sixteen
/// flags at a time: a collision pass at rest marks one particle in a block or none, and a
/// branch on each of the block's 512 flags was most of the whole rule's time (7% of a step of
/// blow-dryer-swarm from t = 8 s, 2026-11-26).
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
/// Out of line and scalar, as collideExactly. Returns the bounces; clears `finite` if a state it
/// wrote is not.
[[gnu::noinline]] std::uint64_t wholeRule(const Arrays& a, std::size_t b, std::size_t n, float restitution,
                                          std::span<const PlaneT<float>> planes, CollisionResponse response,
                                          const std::optional<RoomSurfacesT<float>>& room,
                                          const StartPositions& start, const std::uint32_t* which,
                                          std::size_t marked, bool& finite)
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
/// keeps a block crowded, a hint that changes no result. (It counted the particles the pass
/// moved, four more instructions a vector in its loop: blow-dryer-swarm at rest at 1e6 1.0-1.03e9
/// particle-steps/s against 1.05e9 without them, medians of 12 alternations, 2026-11-26.)
PBA_FOR_EACH_INSTRUCTION_SET
std::uint64_t collideHits(const Arrays& a, std::size_t b, std::size_t n, float restitution,
                          std::span<const PlaneT<float>> planes, CollisionResponse response,
                          const std::optional<RoomSurfacesT<float>>& room, const StartPositions& start, bool& finite,
                          std::size_t& moved)
{
    moved = n;
    if (!room)
        return wholeRule(a, b, n, restitution, planes, response, room, start, nullptr, n, finite);
    alignas(64) std::uint32_t unfinished[kBlock];
    const float back = response == CollisionResponse::Reflect ? 2.0f : 1.0f; // see pushBack
    const auto pass = [&](auto hole) {
        return passInRoom<decltype(hole)::value>(a.px + b, a.py + b, a.pz + b, a.vy + b, start[0], start[1],
                                                 start[2], unfinished, n, *room, restitution, back);
    };
    const PassResult result = room->hasHole() ? pass(std::true_type{}) : pass(std::false_type{});
    finite = finite && result.finite;
    moved = static_cast<std::size_t>(result.bounces) + result.unfinished;
    std::uint64_t bounces = static_cast<std::uint64_t>(result.bounces);
    if (result.unfinished > 0)
        bounces += wholeRule(a, b, n, restitution, planes, response, room, start, unfinished, result.unfinished,
                             finite);
    return bounces;
}

/// The particles of a block marked in `hit`, listed in `index` (room for all that are marked);
/// returns how many, and in `spare` the first clear one. The flags are first packed
/// eight to a byte (a multiplication gathers eight 0/1 bytes into eight bits: one loop, which
/// vectorises), and the scan then visits only the set bits of each 64: a branch a word and one
/// a hit, where a branch every eight flags mispredicted often. `hit` has room for a whole
/// last word of 64.
std::size_t listHits(std::uint8_t* __restrict hit, std::size_t n, std::uint16_t* __restrict index,
                     std::size_t& spare)
{
    std::fill(hit + n, hit + (n + 63) / 64 * 64, std::uint8_t(0));
    alignas(64) std::uint8_t packed[kBlock / 8]; // byte w: flags 8w to 8w + 7, little-endian
    const std::size_t words = (n + 63) / 64;
    for (std::size_t w = 0; w < words * 8; ++w) {
        std::uint64_t eight;
        std::memcpy(&eight, hit + 8 * w, sizeof eight);
        packed[w] = static_cast<std::uint8_t>(eight * 0x0102040810204080ull >> 56); // byte i's bit 0 to bit i
    }
    std::size_t m = 0;
    spare = n;
    for (std::size_t q = 0; q < words; ++q) {
        std::uint64_t bits;
        std::memcpy(&bits, packed + 8 * q, sizeof bits);
        if (spare == n && ~bits != 0) // the first clear one (before any padding: some are clear)
            spare = 64 * q + static_cast<std::size_t>(std::countr_one(bits));
        for (; bits != 0; bits &= bits - 1)
            index[m++] = static_cast<std::uint16_t>(64 * q + static_cast<std::size_t>(std::countr_zero(bits)));
    }
    return m;
}

/// Phase 3, reflect and clamp, for the blocks where few particles met a surface (where rain
/// lands: a handful of the 512): collideHits over just those particles, gathered from
/// several blocks into a batch of their own and scattered back. Over one block's handful,
/// padded to a vector, the rule's pass costs as much as listing and gathering them; over the
/// whole block it cost more (blow-dryer-swarm from t = 2 s at 1e6 on 2 threads: 1.04-1.08e9
/// particle-steps/s without the gathering, 1.24-1.27e9 with it; the same in flight). A
/// particle clear of every surface is left exactly as it was by every part of the rule, and
/// the rule treats each particle by itself, so the result is the same bit for bit (tested). The
/// batch is filled up to whole vectors with copies of one such particle, so its loops have no
/// scalar remainder.
class GatheredHits {
public:
    static constexpr std::size_t kCapacity = 2 * kGatherMax;
    static_assert(kCapacity % kGatherWidth == 0, "a full batch is whole vectors: its padding fits");

    GatheredHits(const Arrays& a, float restitution, std::span<const PlaneT<float>> planes,
                 CollisionResponse response, const std::optional<RoomSurfacesT<float>>& room)
        : m_a(a), m_restitution(restitution), m_planes(planes), m_response(response), m_room(room)
    {
    }

    /// Adds the particles of block b marked in `hit` (at most kGatherMax, and fewer than n), with
    /// their start positions; runs the batch first if they would not fit. Returns its bounces.
    std::uint64_t add(std::size_t b, std::size_t n, std::uint8_t* hit, const float (*start)[kStartRow])
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
        const std::uint64_t bounces = collideHits(gathered, 0, width, m_restitution, m_planes, m_response, m_room,
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
    float m_restitution;
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

/// The acceleration with at most one dryer, swarmAcceleration as a closure holding its fields
/// by value, so the loop that calls it needs no alias checks: gravity, drag with `kDrag`, and
/// the dryer's term push(x). Without drag (`kDrag` false, every built-in swarm scene) the drag
/// is left out rather than multiplied by zero: the same result for every finite velocity, and
/// the loop measured 14% faster (three multiply-adds fewer, and registers to spare for the
/// dryer's constants). One closure type for both: a closure without the unused `drag` measured
/// 1-2% slower in every phase (GCC 12 scheduled the loop otherwise).
/// Gravity's -0 components are made +0 first (g + 0, once), for an upward dryer's force, which
/// may have -0 components: it adds nothing after its products (dryerForceFrom), where it added a
/// zero that made each -0 +0. For any g and f, (g + 0) + f is g + (f + 0) bit for bit, so the
/// sum is as before; with gravity vertical and no drag (every built-in scene) the compiler's
/// fused g.x + radial d.x also rounds as the product alone did, and with a sideways gravity or
/// drag it rounds once where it rounded twice. (Without a dryer the sum changes only for a
/// gravity with a -0 component, whose -0 acceleration becomes +0.)
template <bool kDrag, class Push>
auto accelerationWith(const SwarmKernelFields& fields, Push push)
{
    const Vec3<float> gravity = fields.gravity + Vec3<float>(0.0f);
    return [gravity, drag = fields.dragPerMass, push](const Vec3<float>& x, const Vec3<float>& v) {
        if constexpr (kDrag)
            return gravity + dragForce(drag, v) + push(x); // as swarmAcceleration
        else
            return static_cast<void>(drag), gravity + push(x); // one closure for both (see above)
    };
}

template <DryerAxis kAxis, bool kDrag>
auto oneDryer(const SwarmKernelFields& fields)
{
    return accelerationWith<kDrag>(fields, [dryer = fields.dryer](const Vec3<float>& x) {
        return blowDryerForce<kAxis>(dryer, x);
    });
}

/// Without a dryer, or where one cannot push: oneDryer's acceleration wherever its force is
/// zero (a dryer of zero strength; outside its cone and shaft, where blowDryerMayPush is false),
/// without its two roots and two divisions, the most of its loop's arithmetic. There the dryer's
/// force is a zero vector, +0 or -0 in each component, and so is 0 x at a finite x; gravity
/// plus drag is never -0 (gravity's zeros are +0, see accelerationWith, and a sum that cancels
/// is +0), and adding either zero to anything else leaves it as it was, so the two
/// accelerations are the same bit for bit. The term is 0 x rather than nothing: a constant
/// acceleration lets the compiler take its product with dt out of the loop and round the step
/// differently from the loop with a dryer (it did, for semi-implicit Euler: every particle's
/// last bits). The loop away from the dryer computed the dryer's own zero instead (its offset
/// from the nozzle, its height, their products with zero: ten instructions an evaluation, two a
/// step for velocity Verlet and four for RK4), and measured slower: RK4's 10% in an L1 harness
/// (docs/performance.md, 2026-11-27).
template <bool kDrag>
auto withoutDryer(const SwarmKernelFields& fields)
{
    return accelerationWith<kDrag>(fields, [](const Vec3<float>& x) { return 0.0f * x; });
}

/// The integrator's step for the m particles of block b listed in `index` (integrateAwayBlock's
/// blown ones) with the whole acceleration: gathered into rows of their own, padded to whole
/// vectors with copies of the first, stepped by integrateBlock's loop and scattered back (a
/// scalar loop over them measured slower than the whole block's). Returns whether the states
/// it wrote are finite.
template <Integrator kIntegrator, class Accel>
bool integrateGathered(const Arrays& a, std::size_t b, const std::uint16_t* index, std::size_t m, float dt,
                       Accel accel)
{
    alignas(64) float rows[9][kStartRow]; // the six arrays' gathered states, then start positions
    float* const arrays[6] = {a.px + b, a.py + b, a.pz + b, a.vx + b, a.vy + b, a.vz + b};
    const std::size_t padded = (m + kGatherWidth - 1) / kGatherWidth * kGatherWidth;
    for (std::size_t c = 0; c < 6; ++c) {
        for (std::size_t j = 0; j < m; ++j)
            rows[c][j] = arrays[c][index[j]];
        std::fill(rows[c] + m, rows[c] + padded, rows[c][0]);
    }
    const bool finite = integrateBlock<kIntegrator, false>(rows[0], rows[1], rows[2], rows[3], rows[4], rows[5],
                                                           rows[6], rows[7], rows[8], nullptr, nullptr, nullptr,
                                                           padded, dt, accel);
    for (std::size_t c = 0; c < 6; ++c)
        for (std::size_t j = 0; j < m; ++j)
            arrays[c][index[j]] = rows[c][j];
    return finite;
}

/// integrateInDryer's split for a block (see there): the away loop unless the block is busy.
template <Integrator kIntegrator, DryerAxis kAxis, bool kDrag, class Whole>
bool integrateAwayFromDryer(const Arrays& a, std::size_t b, std::size_t n, float dt, float (*start)[kStartRow],
                            CollisionResponse response, const SwarmKernelFields& fields, const BlowDryerReach& reach,
                            Whole whole)
{
    constexpr std::uint8_t kBusySteps = 64;
    std::uint8_t& busy = a.blowing[b / kBlock];
    if (busy > 0) {
        --busy;
        return integrateBlock<kIntegrator>(a, b, n, dt, start, response, whole);
    }
    alignas(64) std::uint32_t blown[kBlock]; // words: bytes made the loop take 64 particles a vector
    alignas(64) std::uint8_t blownBytes[kBlock + 64]; // room for listHits' last word
    std::size_t count = 0;
    const auto away = [&](auto keepStartVelocity) {
        return integrateAwayBlock<kIntegrator, decltype(keepStartVelocity)::value, kAxis>(
            a.px + b, a.py + b, a.pz + b, a.vx + b, a.vy + b, a.vz + b, start[0], start[1], start[2], start[3],
            start[4], start[5], blown, count, n, dt, reach, withoutDryer<kDrag>(fields));
    };
    bool finite = response == CollisionResponse::Exact ? away(std::true_type{}) : away(std::false_type{});
    if (count == 0)
        return finite;
    alignas(64) std::uint16_t index[kBlock];
    std::size_t spare = 0;
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k)
        blownBytes[k] = static_cast<std::uint8_t>(blown[k]);
    const std::size_t m = listHits(blownBytes, n, index, spare);
    finite = integrateGathered<kIntegrator>(a, b, index, m, dt, whole) && finite;
    if (count > kGatherMax)
        busy = kBusySteps;
    return finite;
}

/// Steps a block with one dryer. The dryer's two roots and two divisions at each evaluation are
/// most of the integration loop's arithmetic (twice a step for velocity Verlet, four times for
/// RK4), while once a swarm has landed well under 1% of it is where the dryer pushes
/// (fountain-1m from t = 2 s: 0.5% in the cone, 0.1% in the shaft). So unless the block is busy
/// (its cone crowded, as when rain falls through it), every particle is stepped with the
/// acceleration away from the dryer and the few the dryer may have pushed again with the whole
/// one (integrateAwayBlock, integrateGathered): the same states. Measured (blow-dryer-swarm, 2
/// threads, the builds alternated, 2026-11-25) from t = 2 s: at 1e6 velocity Verlet 1.2e9
/// particle-steps/s against 0.9e9 and RK4 7.4-7.7e8 against 5.7e8, at 1e7 8.4e8 against 7.1e8
/// and 6.6-6.7e8 against 5.0-5.2e8; in flight (busy blocks: the one loop) the same. The Eulers
/// evaluate once, and keep the one loop: for semi-implicit Euler landed the split was 10-18%
/// slower at 1e7, where the loop waits on memory (0.96-1.02e9 against 1.16-1.17e9), and at 1e6
/// no faster (5-13% faster in one sitting; 7% slower, the median of ten alternations, in
/// another, 2026-11-26), so not even for a swarm that stays in the cache; nor at rest (from t =
/// 8 s, 1e6: 7.1-9.0e8 against 8.4-8.6e8 over four alternations, 2026-11-26). Split a vector of
/// 16 at a time instead (a branch a vector to the one loop or the away one, no gathering: the
/// same states) it was slower still, the integration phase 1.58-1.98 ms of thread time a step
/// against 1.31-1.48 (fountain-1m from t = 3 s, 2026-11-26): the branches and each vector's
/// reductions cost more than the roots they skip. The flags are words: as bytes they made GCC
/// take 64 particles a vector, and the away loop spilled. A block that had more than kGatherMax
/// particles to step again is busy for the next 64 steps. A higher bar, so that rain in flight
/// (a quarter of each block in the cone) takes the split too, measured slower (RK4 with half a
/// block, Verlet with a quarter: RK4 in flight 3.0-3.6e8 against 4.1-4.5e8, 2026-11-26), and
/// again with the away loop's one test (2026-11-27, docs/performance.md): the scatter after the
/// gathered step stalls on the rows the vectorised loop has just stored.
template <Integrator kIntegrator, DryerAxis kAxis, bool kDrag>
bool integrateInDryer(const Arrays& a, std::size_t b, std::size_t n, float dt, float (*start)[kStartRow],
                      CollisionResponse response, const SwarmKernelFields& fields, const BlowDryerReach& reach)
{
    const auto whole = oneDryer<kAxis, kDrag>(fields);
    if constexpr (kIntegrator == Integrator::ForwardEuler || kIntegrator == Integrator::SemiImplicitEuler)
        return integrateBlock<kIntegrator>(a, b, n, dt, start, response, whole);
    else
        return integrateAwayFromDryer<kIntegrator, kAxis, kDrag>(a, b, n, dt, start, response, fields, reach, whole);
}

/// A range's step, block by block: integrate (checking the states are finite as they are
/// written); test which particles are near a surface; the rule for those, gathered from several
/// blocks when few, over the whole block when many (passInRoom in a World's room). Measured
/// against the simplest design, one fused pass a block that integrates and runs the rule's first
/// pass over every surface as selects for every particle, the rare cases after it through a
/// Particle's whole rule (blow-dryer-swarm, 1e6 particles, 2 threads, both built from one tree
/// and alternated, 2026-11-25): the phases 1.35e9 particle-steps/s in flight and 1.28e9 landed,
/// the fused pass 0.94-1.07e9 and 0.82-0.91e9 with all seven surfaces in it, about 1.0e9 and
/// 0.85e9 with only the floor and the grille. The selects cost every particle what the surface
/// test costs only those near a surface (this CPU runs 512-bit operations at half rate), and
/// the fused loop's one long chain (two square roots, two divisions, then the rule) left the
/// out-of-order core less to overlap than two short loops. So the surface test and the
/// gathering stay; the rule itself is one loop (passInRoom). Fusing only where the pass runs
/// over the whole block anyway (a crowded block: integrate, with the dryer's split, then
/// passInRoom's selects on the states still in registers, 2026-11-26) measured no faster
/// either: fountain-1m from t = 8 s 800-900 steps/s both, blow-dryer-swarm from t = 2 s
/// within 2% at 1e6 and 1e7. Loading a block from L1 twice is not what those loops wait on;
/// their instructions are.
template <Integrator kIntegrator>
std::uint64_t stepBlocks(const Arrays& a, std::size_t begin, std::size_t end, const SwarmKernelFields& fields,
                         float restitution, float dt, std::span<const PlaneT<float>> planes,
                         CollisionResponse response)
{
    alignas(64) float start[6][kStartRow];
    alignas(64) std::uint8_t hit[kBlock + 64]; // room for listHits' last word
    std::uint64_t bounces = 0;
    const std::optional<BoxWallsT<float>> box = boxWalls(planes);
    const bool coversAll = box && boxCoversAll(*box, planes);
    const bool exact = response == CollisionResponse::Exact;
    const std::optional<RoomSurfacesT<float>> room = exact ? std::nullopt : roomSurfaces(planes);
    GatheredHits gathered(a, restitution, planes, response, room);
    const auto all = [&](const Vec3<float>& x, const Vec3<float>& v) {
        return swarmAccelerationAll(fields, x, v);
    };
    const bool drag = fields.dragPerMass != 0.0f;
    const BlowDryerReach reach(fields.dryer, dt, glm::length(dvec3(fields.gravity)), fields.dragPerMass);
    PhaseClock clock(a.phases);
    for (std::size_t b = begin; b < end; b += kBlock) {
        const std::size_t n = std::min(kBlock, end - b);
        const auto integrate = [&](auto accel) {
            return integrateBlock<kIntegrator>(a, b, n, dt, start, response, accel);
        };
        // Whether the states the block's loops wrote are finite: swarms are checked every step
        // like bodies, and the flags say where to look for the first bad particle. Each loop
        // that writes the states tests them while they are in registers (a pass of its own
        // over the block measured as long as the surface test).
        bool finite = true;
        if (fields.moreCount > 0 || fields.air)
            finite = integrate(all);
        else if (fields.noDryer)
            finite = drag ? integrate(withoutDryer<true>(fields)) : integrate(withoutDryer<false>(fields));
        else if (fields.dryerUp)
            finite = drag
                ? integrateInDryer<kIntegrator, DryerAxis::Up, true>(a, b, n, dt, start, response, fields, reach)
                : integrateInDryer<kIntegrator, DryerAxis::Up, false>(a, b, n, dt, start, response, fields, reach);
        else
            finite = drag
                ? integrateInDryer<kIntegrator, DryerAxis::Any, true>(a, b, n, dt, start, response, fields, reach)
                : integrateInDryer<kIntegrator, DryerAxis::Any, false>(a, b, n, dt, start, response, fields, reach);
        clock.lap(SwarmPhaseTimes::Integrate);
        // A crowded block (most of it on the floor last step, as a landed swarm is) skips the
        // surface test and takes the collision pass whole, which leaves a clear particle
        // exactly as it was: the same result, without a test that would mark most of the
        // block anyway. It stays crowded while the pass moves more than a batch's worth.
        std::uint8_t& crowded = a.crowded[b / kBlock];
        const bool test = !(room && crowded);
        const std::size_t hits = !test ? n : planes.empty() ? 0 : classifyBlock(a, b, n, planes, box, coversAll, exact, hit);
        clock.lap(SwarmPhaseTimes::SurfaceTest);
        std::size_t moved = 0;
        if (hits > 0 && exact) {
            bounces += collideExactly<kIntegrator>(a, b, n, fields, restitution, dt, planes, start, hit);
            finite = allFinite(a, b, n);
        } else if (hits > 0 && hits <= kGatherMax && hits < n) {
            bounces += gathered.add(b, n, hit, start); // checked again when the batch is resolved
        } else if (hits > 0) {
            bounces += collideHits(a, b, n, restitution, planes, response, room, {start[0], start[1], start[2]},
                                   finite, moved);
        }
        crowded = static_cast<std::uint8_t>(moved > kGatherMax);
        clock.lap(SwarmPhaseTimes::Collide);
        a.finite[b / kBlock] = finite;
        clock.lap(SwarmPhaseTimes::Check);
    }
    bounces += gathered.collide();
    clock.lap(SwarmPhaseTimes::Collide);
    return bounces;
}

/// Every integrator's loop for a range of particles, compiled three times: for AVX-512
/// (x86-64-v4), AVX2 with FMA (x86-64-v3) and the baseline SSE2, the best picked when the
/// program starts. The default build so runs 16 floats an instruction on a CPU that has them
/// without `-march=native`, and still runs everywhere. `flatten` inlines every kernel into each
/// copy, so the integrator, force and collision templates are compiled for that instruction set.
/// (Vector width and fused multiply-adds change the last bits of a result from one kind of CPU
/// to another; on one machine it is the same for every thread count.)
PBA_FOR_EACH_INSTRUCTION_SET
std::uint64_t stepSwarmRange(Integrator integrator, const Arrays& a, std::size_t begin, std::size_t end,
                             const SwarmKernelFields& fields, float restitution, float dt,
                             std::span<const PlaneT<float>> planes, CollisionResponse response)
{
    switch (integrator) {
    case Integrator::ForwardEuler:
        return stepBlocks<Integrator::ForwardEuler>(a, begin, end, fields, restitution, dt, planes, response);
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitGyroscopic: // a point does not turn
        return stepBlocks<Integrator::SemiImplicitEuler>(a, begin, end, fields, restitution, dt, planes,
                                                         response);
    case Integrator::VelocityVerlet:
        return stepBlocks<Integrator::VelocityVerlet>(a, begin, end, fields, restitution, dt, planes,
                                                      response);
    case Integrator::RK4:
        return stepBlocks<Integrator::RK4>(a, begin, end, fields, restitution, dt, planes, response);
    }
    return 0;
}

} // namespace

Swarm::Swarm(const SwarmDesc& desc)
    : m_desc(desc), m_mass(float(desc.mass)), m_restitution(float(desc.restitution)), m_integrator(desc.integrator),
      m_count(desc.count), m_stride(strideFor(desc.count)), m_state(6 * m_stride)
{
    for (std::size_t i = 0; i < desc.count; ++i) {
        const dvec3 x = desc.regionMin + (desc.regionMax - desc.regionMin) *
                                             dvec3(uniform(desc.seed, i, 0), uniform(desc.seed, i, 1), uniform(desc.seed, i, 2));
        const dvec3 v = desc.velocity + desc.velocityJitter * (2.0 * dvec3(uniform(desc.seed, i, 3), uniform(desc.seed, i, 4),
                                                                            uniform(desc.seed, i, 5)) -
                                                               1.0);
        set(i, Vec3<float>(x), Vec3<float>(v));
    }
}

void Swarm::set(std::size_t i, const Vec3<float>& x, const Vec3<float>& v)
{
    array(0)[i] = x.x, array(1)[i] = x.y, array(2)[i] = x.z;
    array(3)[i] = v.x, array(4)[i] = v.y, array(5)[i] = v.z;
    if (!m_clear.empty())
        m_clear[i] = 0; // unknown until the next step tests it
}

std::uint64_t Swarm::stepRange(const SwarmKernelFields& fields, std::span<const PlaneT<float>> planes,
                               CollisionResponse response, float dt, std::size_t begin, std::size_t end)
{
    const Arrays a{array(0),       array(1),        array(2),         array(3),    array(4), array(5),
                   m_clear.data(), m_finite.data(), m_crowded.data(), m_blowing.data(), m_phaseTimes};
    return stepSwarmRange(m_integrator, a, begin, end, fields, m_restitution, dt, planes, response);
}

std::uint64_t Swarm::step(const SwarmFields& swarmFields, std::span<const PlaneT<float>> planes,
                          CollisionResponse response, float dt, int threads)
{
    const SwarmKernelFields fields(swarmFields, 1.0f / m_mass); // once a step, not once a task
    const std::size_t n = size();
    // The remembered "clear of every surface" flags hold only for the surfaces they were
    // computed against: new surfaces (a moved hole, another room) mean testing everything again.
    const bool same = samePlanes(planes, m_clearOf);
    if (response != CollisionResponse::Exact) {
        // Reflect and clamp look at where a step ends only: no flags to keep (or to move).
        m_clear = {};
        m_clearOf.clear();
    } else if (!same || m_clear.size() != n) {
        m_clear.assign(n, std::uint8_t(0));
        m_clearOf.assign(planes.begin(), planes.end());
    }
    m_finite.resize((n + kBlock - 1) / kBlock);
    m_crowded.resize(m_finite.size()); // hints only: a stale one changes no result
    m_blowing.resize(m_finite.size());
    const std::uint64_t bounces = stepAll(fields, planes, response, dt, threads);
    findNonFinite();
    return bounces;
}

void Swarm::findNonFinite()
{
    m_nonFinite.reset();
    for (std::size_t block = 0; block < m_finite.size(); ++block) {
        if (m_finite[block])
            continue;
        for (std::size_t i = block * kBlock; i < std::min(m_count, (block + 1) * kBlock); ++i) {
            const Vec3<float> x = position(i), v = velocity(i);
            if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z)))
                m_nonFinite = NonFiniteParticle{i, "position"};
            else if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)))
                m_nonFinite = NonFiniteParticle{i, "velocity"};
            if (m_nonFinite)
                return;
        }
    }
}

std::uint64_t Swarm::stepAll(const SwarmKernelFields& fields, std::span<const PlaneT<float>> planes,
                             CollisionResponse response, float dt, int threads)
{
    const std::size_t n = size();
    if (threads == 1 || n < kParallelThreshold)
        return stepRange(fields, planes, response, dt, 0, n);
    // Whole blocks per task; a particle's result does not depend on which thread steps it.
    const std::size_t blocks = (n + kBlock - 1) / kBlock;
    auto body = [&] {
        return tbb::parallel_reduce(
            tbb::blocked_range<std::size_t>(0, blocks, 16), std::uint64_t(0),
            [&](const tbb::blocked_range<std::size_t>& r, std::uint64_t sum) {
                return sum + stepRange(fields, planes, response, dt, r.begin() * kBlock, std::min(n, r.end() * kBlock));
            },
            std::plus<>());
    };
    if (threads <= 0 || threads >= tbb::this_task_arena::max_concurrency())
        return body(); // all cores: the default arena, not a new one every step
    tbb::task_arena arena(threads);
    return arena.execute(body);
}

} // namespace pba
