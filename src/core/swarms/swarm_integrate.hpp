#pragma once
// Phase 1 of a swarm's step, integration: the integrator's loop over a block, the acceleration
// as closures the loop can vectorise, and the split of a block into the particles the blow
// dryer may push and the rest. Private to src/core/swarms/swarm.cpp (see swarm_block.hpp).
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "pba/detail/swarm_kernel.hpp"
#include "pba/swarm.hpp"
#include "swarms/swarm_block.hpp"

namespace pba {

// Internal linkage, as when this lived in swarm.cpp: the one file that includes it.
namespace {

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

/// Phase 1 of a block: the plain integrator step for every particle, a loop with no branches
/// the vectoriser cannot turn into selects. The start states are kept for phase 2.
template <Integrator kIntegrator, bool kKeepStartVelocity, class Accel>
bool integrateBlock(float* __restrict px, float* __restrict py, float* __restrict pz, float* __restrict vx,
                    float* __restrict vy, float* __restrict vz, float* __restrict s0, float* __restrict s1,
                    float* __restrict s2, float* __restrict s3, float* __restrict s4, float* __restrict s5,
                    std::size_t n, float dt, Accel accel)
{
    // Distinct arrays (restrict) and an acceleration holding its fields by value: what lets
    // the compiler vectorise this loop without alias checks. With more than one dryer or the
    // air's terms (swarmAccelerationAll) the acceleration loops over the dryers and the loop is
    // scalar: 4 integrators, with and without the start velocities, in 3 instruction sets.
    std::uint32_t exponent = 0;
    // vectorised: checked, but 24 scalar copies (swarmAccelerationAll's loop over dryers)
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
/// would have given it at every point, so it took the same step. `kOnce` (no drag): `away` is
/// evaluated once a particle, at its start, and serves every stage.
template <Integrator kIntegrator, bool kKeepStartVelocity, DryerAxis kAxis, bool kOnce, class Away>
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
        if constexpr (kOnce) {
            // Without drag, away's acceleration is g + 0 x: g at every finite point, so it is
            // taken once, at the start, for every stage. RK4 no longer forms its three stage
            // points nor their zero terms, which nothing else reads (a step whose stage point
            // overflows ends beyond the largest float either way, and is reported): RK4 up to
            // about a tenth faster landed (docs/performance.md). Captured as floats: a closure
            // holding a Vec3 left the loop scalar ("more than one data ref").
            const Vec3<float> a0 = away(x0, v0);
            const float ax = a0.x, ay = a0.y, az = a0.z;
            integrateAs<kIntegrator>(x, v, dt, [ax, ay, az](const Vec3<float>&, const Vec3<float>&) {
                return Vec3<float>(ax, ay, az);
            });
        } else {
            integrateAs<kIntegrator>(x, v, dt, away);
        }
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
bool integrateBlock(const Arrays& a, std::size_t b, std::size_t n, float dt, float (*start)[kBlock],
                    CollisionResponse response, Accel accel)
{
    if (response == CollisionResponse::Exact)
        return integrateBlock<kIntegrator, true>(a.px + b, a.py + b, a.pz + b, a.vx + b, a.vy + b, a.vz + b, start[0],
                                          start[1], start[2], start[3], start[4], start[5], n, dt, accel);
    else
        return integrateBlock<kIntegrator, false>(a.px + b, a.py + b, a.pz + b, a.vx + b, a.vy + b, a.vz + b, start[0],
                                           start[1], start[2], start[3], start[4], start[5], n, dt, accel);
}

/// The acceleration with at most one dryer, swarmAcceleration as a closure holding its fields
/// by value, so the loop that calls it needs no alias checks: gravity, drag with `kDrag`, and
/// the dryer's term push(x). Without drag (`kDrag` false, every built-in swarm scene) the drag
/// is left out rather than multiplied by zero: the same result for every finite velocity, and
/// the loop is faster (three multiply-adds fewer, and registers to spare for the dryer's
/// constants). One closure type for both: a closure without the unused `drag` was no faster
/// (GCC scheduled the loop otherwise).
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
/// step for velocity Verlet and four for RK4), and was slower (docs/performance.md).
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
    alignas(64) float rows[9][kBlock]; // the six arrays' gathered states, then start positions
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
bool integrateAwayFromDryer(const Arrays& a, std::size_t b, std::size_t n, float dt, float (*start)[kBlock],
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
        return integrateAwayBlock<kIntegrator, decltype(keepStartVelocity)::value, kAxis, !kDrag>(
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

/// Steps a block with one dryer. Each evaluation of the dryer's force is most of the loop's
/// arithmetic (two a step for velocity Verlet, four for RK4), while once a swarm has landed well
/// under 1% of it is where the dryer pushes. So, unless the block is busy (rain falling through
/// the cone), those two integrators step every particle with the acceleration away from the
/// dryer and step again, with the whole one, the few it may have pushed (integrateAwayBlock,
/// integrateGathered): the same states, a fifth to a third faster landed. The Eulers evaluate
/// once and keep the one loop: every split tried for them (by block, by vector of 16 or 32) cost
/// more than the roots it skipped. A block that had more than kGatherMax particles to step again
/// is busy for the next 64 steps: gathering more than that, as in flight, stalls on the
/// scatter. (The measurements: docs/performance.md, the design-choice table.)
template <Integrator kIntegrator, DryerAxis kAxis, bool kDrag>
bool integrateInDryer(const Arrays& a, std::size_t b, std::size_t n, float dt, float (*start)[kBlock],
                      CollisionResponse response, const SwarmKernelFields& fields, const BlowDryerReach& reach)
{
    const auto whole = oneDryer<kAxis, kDrag>(fields);
    if constexpr (kIntegrator == Integrator::ForwardEuler || kIntegrator == Integrator::SemiImplicitEuler)
        return integrateBlock<kIntegrator>(a, b, n, dt, start, response, whole);
    else
        return integrateAwayFromDryer<kIntegrator, kAxis, kDrag>(a, b, n, dt, start, response, fields, reach, whole);
}


/// Phase 1 of a block: the integration loop the swarm's fields call for. Any force beyond
/// gravity, drag and one dryer, or the air's velocity terms: the whole acceleration
/// (swarmAccelerationAll); otherwise a loop compiled for what there is (with drag or without,
/// with no dryer, an upward one or one at any angle). Returns whether the states it wrote are
/// finite.
template <Integrator kIntegrator>
bool integrateFor(const Arrays& a, std::size_t b, std::size_t n, float dt, float (*start)[kBlock],
                  CollisionResponse response, const SwarmKernelFields& fields, bool drag, const BlowDryerReach& reach)
{
    const auto integrate = [&](auto accel) {
        return integrateBlock<kIntegrator>(a, b, n, dt, start, response, accel);
    };
    if (fields.moreCount > 0 || fields.air)
        return integrate([&](const Vec3<float>& x, const Vec3<float>& v) {
            return swarmAccelerationAll(fields, x, v);
        });
    if (fields.noDryer)
        return drag ? integrate(withoutDryer<true>(fields)) : integrate(withoutDryer<false>(fields));
    if (fields.dryerUp)
        return drag ? integrateInDryer<kIntegrator, DryerAxis::Up, true>(a, b, n, dt, start, response, fields, reach)
                    : integrateInDryer<kIntegrator, DryerAxis::Up, false>(a, b, n, dt, start, response, fields, reach);
    return drag ? integrateInDryer<kIntegrator, DryerAxis::Any, true>(a, b, n, dt, start, response, fields, reach)
                : integrateInDryer<kIntegrator, DryerAxis::Any, false>(a, b, n, dt, start, response, fields, reach);
}

} // namespace

} // namespace pba
