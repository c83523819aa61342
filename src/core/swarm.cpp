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
    SwarmPhaseTimes* phases = nullptr; ///< where to add each phase's time, if anywhere
};

/// Adds the time since its last lap to a phase's total; does nothing without a SwarmPhaseTimes.
class PhaseClock {
public:
    explicit PhaseClock(SwarmPhaseTimes* times) : m_times(times)
    {
        if (m_times)
            m_last = std::chrono::steady_clock::now();
    }
    void lap(SwarmPhaseTimes::Phase phase)
    {
        if (!m_times)
            return;
        const auto now = std::chrono::steady_clock::now();
        const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(now - m_last).count();
        m_times->nanoseconds[phase].fetch_add(static_cast<std::uint64_t>(ns), std::memory_order_relaxed);
        m_last = now;
    }

private:
    SwarmPhaseTimes* m_times;
    std::chrono::steady_clock::time_point m_last{};
};

/// Whether n floats are all finite, by their exponent bits: an integer OR over the block, which
/// vectorises (a float sum would not, without reassociation) and costs a fraction of a step.
bool allFinite(const Arrays& a, std::size_t b, std::size_t n)
{
    // One pass over the six arrays with one OR accumulator: an infinity or a NaN is the only
    // float whose exponent bits are all set. (Six separate reductions measured slower.)
    const float* __restrict arrays[6] = {a.px + b, a.py + b, a.pz + b, a.vx + b, a.vy + b, a.vz + b};
    std::uint32_t special = 0;
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k) {
        for (const float* values : arrays) {
            std::uint32_t bits;
            std::memcpy(&bits, values + k, sizeof bits);
            special |= static_cast<std::uint32_t>((bits & 0x7f800000u) == 0x7f800000u);
        }
    }
    return special == 0;
}

/// Phase 1 of a block: the plain integrator step for every particle, a loop with no branches
/// the vectoriser cannot turn into selects. The start states are kept for phase 2.
template <Integrator kIntegrator, bool kKeepStartVelocity, class Accel>
void integrateBlock(float* __restrict px, float* __restrict py, float* __restrict pz, float* __restrict vx,
                    float* __restrict vy, float* __restrict vz, float* __restrict s0, float* __restrict s1,
                    float* __restrict s2, float* __restrict s3, float* __restrict s4, float* __restrict s5,
                    std::size_t n, float dt, Accel accel)
{
    // Distinct arrays (restrict) and an acceleration holding its fields by value: what lets
    // the compiler vectorise this loop without alias checks.
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k) {
        Vec3<float> x(px[k], py[k], pz[k]);
        Vec3<float> v(vx[k], vy[k], vz[k]);
        s0[k] = x.x, s1[k] = x.y, s2[k] = x.z;
        if constexpr (kKeepStartVelocity) // only the exact response redoes the step
            s3[k] = v.x, s4[k] = v.y, s5[k] = v.z;
        integrateAs<kIntegrator>(x, v, dt, accel);
        px[k] = x.x, py[k] = x.y, pz[k] = x.z;
        vx[k] = v.x, vy[k] = v.y, vz[k] = v.z;
    }
}

template <Integrator kIntegrator, class Accel>
void integrateBlock(const Arrays& a, std::size_t b, std::size_t n, float dt, float (*start)[kStartRow],
                    CollisionResponse response, Accel accel)
{
    if (response == CollisionResponse::Exact)
        integrateBlock<kIntegrator, true>(a.px + b, a.py + b, a.pz + b, a.vx + b, a.vy + b, a.vz + b, start[0],
                                          start[1], start[2], start[3], start[4], start[5], n, dt, accel);
    else
        integrateBlock<kIntegrator, false>(a.px + b, a.py + b, a.pz + b, a.vx + b, a.vy + b, a.vz + b, start[0],
                                           start[1], start[2], start[3], start[4], start[5], n, dt, accel);
}

/// Phase 2 of a block: which particles need a collision rule, marked in `hit`; returns how many
/// (none in most blocks of a swarm in flight). For reflect and clamp, those that ended the step
/// within a surface's contact tolerance (or beyond it): their rules look at where the step
/// ended. The exact response also redoes the steps that started there; whether a particle
/// started clear is remembered from its last step (`remember`), so only the ends are tested
/// here. `coversAll`: a particle clear of the box's walls is clear of every plane
/// (boxCoversAll), so they are the whole test, and no margins are needed.
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

/// The planes some of the n positions are beyond: those the reflect and clamp rules' first pass
/// must visit (a room's walls, and any other axis-aligned plane, from the positions' bounds).
/// Worked out only for the blocks, or the gathered particles, that met a surface.
std::uint64_t crossedPlanes(std::span<const PlaneT<float>> planes, const float* x, const float* y, const float* z,
                            std::size_t n)
{
    std::uint64_t crossed = 0;
    const BoundsT<float> bounds = boundsOf(x, y, z, n);
    alignas(64) float unused[kBlock]; // lowerClearance's margins: only its count is wanted here
    for (std::size_t p = 0; p < planes.size(); ++p) {
        bool beyond = false;
        if (planes[p].axis() >= 0) {
            beyond = bounds.beyond(planes[p]);
        } else {
            std::fill_n(unused, n, std::numeric_limits<float>::infinity());
            beyond = lowerClearance(planes[p], x, y, z, n, unused) > 0;
        }
        if (beyond)
            crossed |= std::uint64_t(1) << std::min<std::size_t>(p, 63);
    }
    return crossed;
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

/// The first pass of the reflect (kMirror) or clamp rule over one plane for a whole block: the
/// same mirrorBack/snapBack a Particle uses, branch-free, so this is a vectorised loop (a
/// particle inside the plane is left exactly as it was). Compiled apart for a plane with a hole,
/// whose pass also keeps the particles in its shaft within the shaft's wall, and for each form
/// of the plane's geometry (a wall of the room as an AxisPlaneT).
template <bool kMirror, bool kHole, class Geometry>
int passOverPlane(const Geometry plane, float restitution, float* __restrict px, float* __restrict py,
                  float* __restrict pz, float* __restrict vx, float* __restrict vy, float* __restrict vz,
                  const float* __restrict s0, const float* __restrict s1, const float* __restrict s2, std::size_t n)
{
    int bounces = 0;
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3<float> from(s0[k], s1[k], s2[k]);
        Vec3<float> x(px[k], py[k], pz[k]);
        Vec3<float> v(vx[k], vy[k], vz[k]);
        // Counted apart and then added: a bounce off the plane and one off its shaft's wall
        // exclude each other, and GCC, seeing that, made the running sum itself the operand of
        // a select, which its vectoriser does not take as a sum (the loop ran scalar).
        int bounced = 0;
        if constexpr (kMirror)
            mirrorBack<kHole>(plane, restitution, from, x, v, bounced);
        else
            snapBack<kHole>(plane, restitution, from, x, v, bounced);
        bounces += bounced;
        px[k] = x.x, py[k] = x.y, pz[k] = x.z;
        vx[k] = v.x, vy[k] = v.y, vz[k] = v.z;
    }
    return bounces;
}

template <bool kMirror>
int passOverPlane(const PlaneT<float>& plane, float restitution, const Arrays& a, std::size_t b,
                  const StartPositions& start, std::size_t n)
{
    return withPlaneGeometry(plane, [&](const auto geometry) {
        const auto pass = [&](auto hole) {
            return passOverPlane<kMirror, decltype(hole)::value>(geometry, restitution, a.px + b, a.py + b,
                                                                 a.pz + b, a.vx + b, a.vy + b, a.vz + b, start[0],
                                                                 start[1], start[2], n);
        };
        return plane.holeRadius > 0.0f ? pass(std::true_type{}) : pass(std::false_type{});
    });
}

/// The rest of the rule for the few particles still outside after the first pass (and, for
/// reflect, the fold): a corner, a shaft's rim. The same function a Particle uses, told
/// which passes are done. Out of line, as collideExactly.
[[gnu::noinline]] std::uint64_t finishRule(const Arrays& a, std::size_t begin, std::size_t n, float restitution,
                                           std::span<const PlaneT<float>> planes, CollisionResponse response,
                                           const StartPositions& start, const std::uint8_t* outside)
{
    std::uint64_t bounces = 0;
    for (std::size_t k = 0; k < n; ++k) {
        if (!outside[k])
            continue;
        const std::size_t i = begin + k;
        const Vec3<float> from(start[0][k], start[1][k], start[2][k]);
        Vec3<float> x(a.px[i], a.py[i], a.pz[i]);
        Vec3<float> v(a.vx[i], a.vy[i], a.vz[i]);
        bounces += response == CollisionResponse::Reflect ? reflectAfterStep(planes, restitution, from, x, v, 2)
                                                          : clampAfterStep(planes, restitution, from, x, v, 1);
        a.px[i] = x.x, a.py[i] = x.y, a.pz[i] = x.z;
        a.vx[i] = v.x, a.vy[i] = v.y, a.vz[i] = v.z;
    }
    return bounces;
}

/// The walls of a box whose depths markOutside takes in one loop: those without a hole (a wall
/// with one keeps an infinite bound and is tested by itself, shaft and all).
struct DepthBox {
    std::array<float, 3> lo{}, hi{};
    std::uint64_t mask = 0; ///< the planes it covers

    DepthBox(const std::optional<BoxWallsT<float>>& box, std::span<const PlaneT<float>> planes)
    {
        constexpr float kInf = std::numeric_limits<float>::infinity();
        lo.fill(-kInf);
        hi.fill(kInf);
        if (!box)
            return;
        for (std::size_t w = 0; w < 6; ++w) { // low x, high x, low y, ... as BoxWallsT::plane
            const auto p = static_cast<std::size_t>(box->plane[w]);
            if (planes[p].holeRadius > 0.0f)
                continue;
            const std::size_t axis = w / 2;
            if (w % 2 == 0)
                lo[axis] = box->lo[axis];
            else
                hi[axis] = box->hi[axis];
            mask |= std::uint64_t(1) << p;
        }
    }
};

/// Phase 4 of a block: which particles are still outside a surface after the first pass (one in
/// a hole's shaft is not). Returns how many.
std::size_t markOutside(const Arrays& a, std::size_t b, std::size_t n, std::span<const PlaneT<float>> planes,
                        const DepthBox& box, std::uint8_t* __restrict outside)
{
    alignas(64) float depth[kBlock];
    std::fill_n(depth, n, std::numeric_limits<float>::infinity());
    if (box.mask != 0)
        lowerDepthInBox(box.lo, box.hi, a.px + b, a.py + b, a.pz + b, n, depth);
    for (std::size_t p = 0; p < planes.size(); ++p)
        if (p >= 64 || (box.mask >> p & 1u) == 0)
            lowerDepth(planes[p], a.px + b, a.py + b, a.pz + b, n, depth);
    std::uint32_t count = 0;
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k) {
        outside[k] = depth[k] < 0.0f;
        count += outside[k];
    }
    return count;
}

/// The reflect rule's later passes between two walls of the box, for a block with particles
/// still outside after the first: the closed-form fold a Particle uses, one vectorised loop.
/// Whether any of the n coordinates is outside the slab.
bool anyOutsideSlab(const SlabT<float> slab, const float* __restrict c, std::size_t n)
{
    std::uint32_t outside = 0;
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k)
        outside += static_cast<std::uint32_t>((c[k] < slab.lo) | (c[k] > slab.hi));
    return outside > 0;
}

/// (The count is a float sum: exact below 2^24 bounces a block and a step.)
std::uint64_t foldBlock(const SlabT<float> slab, float restitution, float* __restrict c, float* __restrict cv,
                        std::size_t n)
{
    float bounces = 0.0f;
    // vectorised: checked
    for (std::size_t k = 0; k < n; ++k)
        bounces += foldIntoSlab(slab, restitution, c[k], cv[k]);
    return static_cast<std::uint64_t>(bounces);
}

/// Phase 3 of a block, reflect and clamp responses: the rule's first pass plane by plane over the
/// whole block, then (phase 4) which particles are still outside. A plane no particle of the
/// block crossed is skipped (most of a room's walls, most steps); a particle sent across such a
/// plane by another's rule (a corner) is among those still outside. Particles still outside
/// after a reflect pass (faster than the room is wide) are folded into the box's slabs, whole
/// block at once; the rest of the rule sees to any still outside after that.
std::uint64_t collideAfterStep(const Arrays& a, std::size_t b, std::size_t n, float restitution,
                               std::span<const PlaneT<float>> planes, CollisionResponse response,
                               const StartPositions& start, std::uint64_t planesCrossed, const DepthBox& box)
{
    std::uint64_t bounces = 0;
    for (std::size_t p = 0; p < planes.size(); ++p) {
        if ((planesCrossed >> std::min<std::size_t>(p, 63) & 1u) == 0)
            continue;
        const PlaneT<float>& plane = planes[p];
        bounces += response == CollisionResponse::Reflect ? passOverPlane<true>(plane, restitution, a, b, start, n)
                                                          : passOverPlane<false>(plane, restitution, a, b, start, n);
    }
    alignas(64) std::uint8_t outside[kBlock];
    std::size_t count = markOutside(a, b, n, planes, box, outside);
    if (count > 0 && response == CollisionResponse::Reflect) {
        // Particles still outside are mostly at a corner or a shaft's rim, inside every slab: a
        // slab is folded only when some particle is beyond it.
        std::array<SlabT<float>, 3> slabs;
        const int slabCount = boxSlabs(planes, slabs);
        bool folded = false;
        for (int s = 0; s < slabCount; ++s) {
            const SlabT<float>& slab = slabs[std::size_t(s)];
            float* position = slab.axis == 0 ? a.px : slab.axis == 1 ? a.py : a.pz;
            float* velocity = slab.axis == 0 ? a.vx : slab.axis == 1 ? a.vy : a.vz;
            if (anyOutsideSlab(slab, position + b, n)) {
                bounces += foldBlock(slab, restitution, position + b, velocity + b, n);
                folded = true;
            }
        }
        if (folded)
            count = markOutside(a, b, n, planes, box, outside);
    }
    if (count > 0)
        bounces += finishRule(a, b, n, restitution, planes, response, start, outside);
    return bounces;
}

/// Phase 3, reflect and clamp, for a block or a gathered batch with particles at a surface: the
/// planes they crossed, then collideAfterStep. Compiled once for each instruction set, apart
/// from the integration loops that call it: the collision code does not depend on the
/// integrator, and inlined into each integrator's loop it was compiled four times over (with
/// the walls' geometry compiled for each axis, a sanitizer build of this file took 20 minutes).
PBA_FOR_EACH_INSTRUCTION_SET
std::uint64_t collideBlock(const Arrays& a, std::size_t b, std::size_t n, float restitution,
                           std::span<const PlaneT<float>> planes, CollisionResponse response,
                           const StartPositions& start, const DepthBox& box)
{
    const std::uint64_t crossed = crossedPlanes(planes, a.px + b, a.py + b, a.pz + b, n);
    return collideAfterStep(a, b, n, restitution, planes, response, start, crossed, box);
}

/// The particles of a block marked in `hit` (at most kGatherMax, and fewer than n), listed in
/// `index`; returns how many, and in `spare` the first clear one. The flags are first packed
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
/// lands: a handful of the 512): collideAfterStep over just those particles, gathered from
/// several blocks into a batch of their own and scattered back. Over a whole block the rule's
/// passes, the still-outside test and the wall counts cost more than the integration; over one
/// block's handful, padded to a vector, they cost as much as listing and gathering them. A
/// particle clear of every surface is left exactly as it was by every part of the rule, and
/// the rule treats each particle by itself, so the result is the same bit for bit (tested). The
/// batch is filled up to whole vectors with copies of one such particle, so its loops have no
/// scalar remainder.
class GatheredHits {
public:
    static constexpr std::size_t kCapacity = 2 * kGatherMax;
    static_assert(kCapacity % kGatherWidth == 0, "a full batch is whole vectors: its padding fits");

    GatheredHits(const Arrays& a, float restitution, std::span<const PlaneT<float>> planes,
                 CollisionResponse response, const DepthBox& depthBox)
        : m_a(a), m_restitution(restitution), m_planes(planes), m_response(response), m_depthBox(depthBox)
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
        const Arrays gathered{m_state[0], m_state[1], m_state[2], m_state[3], m_state[4], m_state[5], nullptr, nullptr, nullptr};
        const std::uint64_t bounces = collideBlock(gathered, 0, width, m_restitution, m_planes, m_response,
                                                   {m_from[0], m_from[1], m_from[2]}, m_depthBox);
        float* const arrays[6] = {m_a.px, m_a.py, m_a.pz, m_a.vx, m_a.vy, m_a.vz};
        for (std::size_t j = 0; j < m_count; ++j) {
            bool finite = true;
            for (std::size_t c = 0; c < 6; ++c) {
                arrays[c][m_index[j]] = m_state[c][j];
                finite = finite && std::isfinite(m_state[c][j]);
            }
            if (!finite) // its block was checked before its collision was resolved here
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
    const DepthBox& m_depthBox;
    std::size_t m_count = 0;
    bool m_haveSpare = false;
    std::array<float, 9> m_spare{}; ///< a clear particle's state and start: the padding
    std::array<std::size_t, kCapacity> m_index;
    alignas(64) float m_state[6][kCapacity];
    alignas(64) float m_from[3][kCapacity];
};

/// The acceleration with at most one dryer, swarmAcceleration as a closure holding its fields
/// by value, so the loop that calls it needs no alias checks. Without drag (`kDrag` false, every
/// built-in swarm scene) the term is left out rather than multiplied by zero: the same result
/// for every finite velocity, and the loop measured 14% faster (three multiply-adds fewer, and
/// registers to spare for the dryer's constants).
template <DryerAxis kAxis, bool kDrag>
auto oneDryer(const SwarmKernelFields& fields)
{
    return [gravity = fields.gravity, drag = fields.dragPerMass, dryer = fields.dryer](const Vec3<float>& x,
                                                                                      const Vec3<float>& v) {
        if constexpr (kDrag)
            return gravity + dragForce(drag, v) + blowDryerForce<kAxis>(dryer, x); // as swarmAcceleration
        else
            return gravity + blowDryerForce<kAxis>(dryer, x);
    };
}

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
    const DepthBox depthBox(box, planes);
    GatheredHits gathered(a, restitution, planes, response, depthBox);
    const auto all = [&](const Vec3<float>& x, const Vec3<float>& v) {
        return swarmAccelerationAll(fields, x, v);
    };
    const bool drag = fields.dragPerMass != 0.0f;
    PhaseClock clock(a.phases);
    for (std::size_t b = begin; b < end; b += kBlock) {
        const std::size_t n = std::min(kBlock, end - b);
        const auto integrate = [&](auto accel) { integrateBlock<kIntegrator>(a, b, n, dt, start, response, accel); };
        if (fields.moreCount > 0 || fields.air)
            integrate(all);
        else if (fields.dryerUp)
            drag ? integrate(oneDryer<DryerAxis::Up, true>(fields)) : integrate(oneDryer<DryerAxis::Up, false>(fields));
        else
            drag ? integrate(oneDryer<DryerAxis::Any, true>(fields)) : integrate(oneDryer<DryerAxis::Any, false>(fields));
        clock.lap(SwarmPhaseTimes::Integrate);
        const bool exact = response == CollisionResponse::Exact;
        const std::size_t hits = planes.empty() ? 0 : classifyBlock(a, b, n, planes, box, coversAll, exact, hit);
        clock.lap(SwarmPhaseTimes::SurfaceTest);
        if (hits > 0 && exact) {
            bounces += collideExactly<kIntegrator>(a, b, n, fields, restitution, dt, planes, start, hit);
        } else if (hits > 0 && hits <= kGatherMax && hits < n) {
            bounces += gathered.add(b, n, hit, start); // checked again when the batch is resolved
        } else if (hits > 0) {
            bounces += collideBlock(a, b, n, restitution, planes, response, {start[0], start[1], start[2]},
                                    depthBox);
        }
        clock.lap(SwarmPhaseTimes::Collide);
        // The check phase, while the block is still in L1: swarms are checked every step like
        // bodies, and the flags say where to look for the first bad particle. (After the step,
        // over the whole range, the same check measured 15-25% of a step: the arrays again
        // from L3 or memory.)
        a.finite[b / kBlock] = allFinite(a, b, n);
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
    const Arrays a{array(0), array(1), array(2), array(3), array(4), array(5), m_clear.data(), m_finite.data(),
                   m_phaseTimes};
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
