#pragma once
// The blow dryer's force kernel: an implementation detail, not pba's API. Its templates stay in a
// header because the swarm's loops (src/core), the jet's watch (pba::study), the scene reader's
// check of a swarm's fields and the tests inline them into their own vectorised loops; what a
// program calls is pba/blow_dryer.hpp's.
#include <algorithm>
#include <cmath>

#include "pba/blow_dryer.hpp"
#include "pba/math.hpp"

namespace pba {

/// The field with its choices turned into numbers (each falloff a cubic's coefficients, the
/// direction a weight), so the force is arithmetic only: a swarm loop holds one of these and
/// vectorises; enums in the loop would stop it.
template <class T>
struct BlowDryerKernelT {
    Vec3<T> nozzle, axis;
    T height, nozzleRadius, inverseHeight, spread; ///< H, r0, 1 / H and R - r0
    T flowSpread;         ///< R - r0 for cone-flow, 0 for vertical: the weight of rho in the direction
    FalloffCubic<T> axial; ///< the strength times the axial profile: the force on the axis
    FalloffCubic<T> radial;
    T shaftRadius2; ///< r0^2 for a dryer in the floor, 0 (no shaft) otherwise
    T shaftPush;    ///< the force in the shaft, along the axis
    // The air terms (used by blowDryerForce<..., true> only):
    FalloffCubic<T> axialProfile; ///< the axial profile alone (w's first factor)
    T airDrag;  ///< c (times scale), 0 without air speed
    T pull;     ///< beta U^2 (times scale)
    // A ball's air (air density on; zero otherwise):
    T airPerPush;    ///< U / (scale strength): the air's velocity per unit of the push
    T dragPerArea;   ///< (1/2) rho_a C_d (times scale): a ball's drag over its cross-section
    T pullPerVolume; ///< rho_a U^2 (times scale): a ball's pull over its volume

    BlowDryerKernelT() : BlowDryerKernelT(BlowDryerFieldT<T>{}) {}
    /// `scale` multiplies the force: a swarm passes 1 / m and gets the dryer's acceleration,
    /// one multiplication a particle fewer.
    explicit BlowDryerKernelT(const BlowDryerFieldT<T>& f, T scale = T(1))
        : nozzle(f.nozzle), axis(f.axis), height(f.height), nozzleRadius(f.nozzleRadius),
          inverseHeight(T(1) / f.height), spread(f.topRadius - f.nozzleRadius),
          flowSpread(f.direction == FlowDirection::ConeFlow ? spread : T(0)), axial(f.axialFalloff, scale * f.strength),
          radial(f.radialFalloff), shaftRadius2(f.shaft ? f.nozzleRadius * f.nozzleRadius : T(0)),
          shaftPush(scale * f.strength), axialProfile(f.axialFalloff), airDrag(scale * f.airDrag()),
          pull(scale * f.axisPull * f.airSpeed * f.airSpeed),
          airPerPush(f.airDensity > T(0) && f.strength != T(0) ? f.airSpeed / (scale * f.strength) : T(0)),
          dragPerArea(f.airDensity > T(0) && f.airSpeed > T(0) ? scale * T(0.5) * f.airDensity * f.dragCoefficient : T(0)),
          pullPerVolume(dragPerArea != T(0) ? scale * f.airDensity * f.airSpeed * f.airSpeed : T(0))
    {
    }
    /// Whether the air terms are on: then only blowDryerForce<..., true> gives the force.
    bool hasAirTerms() const { return airDrag != T(0) || pull != T(0) || dragPerArea != T(0); }
    /// Whether a ball of radius r feels the air by its size (blowDryerForce's ball branch).
    bool movesBall(T r) const { return dragPerArea != T(0) && r > T(0); }
};

/// What the kernel knows of the dryer's axis when it is compiled: nothing (`Any`), or that it is
/// exactly +y (`Up`, every built-in scene), which turns the axial and radial projections into
/// picking coordinates: a sixth fewer multiplications in a swarm step. Both are the same
/// arithmetic otherwise.
enum class DryerAxis { Any, Up };

/// Where a point x lies in the dryer's frame: its offset d from the nozzle, its height h along
/// the axis, its offset rho across the axis and rho's squared length r2, and across2, the
/// squared distance from the nozzle across the floor (the shaft's wall is measured across the
/// floor, which is horizontal whatever the axis). Upward (`Up`) h is d.y, rho is (d.x, 0, d.z)
/// and r2 is across2, with none of the products by the axis's zero components. The force and
/// the tests of where it may push all start from it, so they see the same h and r2, rounding
/// for rounding; the parts a caller does not use cost nothing once it is inlined. Built in
/// place (`const auto [d, h, rho, r2, across2] = DryerFrameT<...>(...)`): a function returning
/// it made GCC copy it as a whole, and a swarm loop that tests and integrates stopped
/// vectorising.
template <DryerAxis kAxis, class T>
struct DryerFrameT {
    static constexpr bool kUp = kAxis == DryerAxis::Up;
    Vec3<T> d;
    T h;
    Vec3<T> rho;
    T r2;
    T across2;

    DryerFrameT(const Vec3<T>& nozzle, const Vec3<T>& axis, const Vec3<T>& x)
        : d(x - nozzle), h(kUp ? d.y : glm::dot(d, axis)), rho(kUp ? Vec3<T>(d.x, T(0), d.z) : d - h * axis),
          r2(kUp ? d.x * d.x + d.z * d.z : glm::dot(rho, rho)), across2(kUp ? r2 : d.x * d.x + d.z * d.z)
    {
    }
};

/// Whether x lies under the floor's hole of a dryer in the floor (the shaft and the dryer below
/// its grille): below the nozzle and within r0 of it across the floor (the floor is horizontal,
/// whatever the axis). No lower bound: a particle resting on the grille is in it whatever the
/// rounding of the grille's height. `below` is the frame's d.y, `across2` its across2.
template <class T>
inline bool inBlowDryerShaft(const BlowDryerKernelT<T>& f, T below, T across2)
{
    return (below < T(0)) & (across2 < f.shaftRadius2);
}

/// blowDryerForce's closing expression: along the axis, across it (times rho), and with
/// `kExtra` the air's velocity term.
/// Without it, nothing is added: adding a zero only turned a component's -0 into +0, additions
/// a particle in a swarm's loop, and (upward) kept the compiler from fusing the products into
/// the sum with gravity (a swarm's accelerationWith, in swarm_integrate.hpp, makes that sum round as
/// before; a -0 component adds to gravity as +0 does).
template <DryerAxis kAxis, bool kExtra, class T>
inline Vec3<T> dryerForceFrom(const BlowDryerKernelT<T>& f, T along, T radial, const Vec3<T>& d, const Vec3<T>& rho,
                              const Vec3<T>& extra)
{
    if constexpr (kAxis == DryerAxis::Up && !kExtra)
        return Vec3<T>(radial * d.x, along, radial * d.z);
    else if constexpr (kAxis == DryerAxis::Up)
        return Vec3<T>(radial * d.x, along, radial * d.z) + extra;
    else if constexpr (!kExtra)
        return along * f.axis + radial * rho;
    else
        return along * f.axis + radial * rho + extra;
}

/// The force of the field at x and, with `kAir`, velocity v (see the header's comment; without
/// kAir the seed's force, which does not depend on v, and which equals the kAir force whenever
/// the air terms are off).
///
/// Written for the swarm loop, where square roots and divisions are the slow instructions:
/// two of each a particle, none waiting for another. With q = R(h) (the radius here) and
/// c = w (R - r0) / q (w = 1 for cone-flow, 0 for vertical), the flow direction is H axis + c rho,
/// and since rho is perpendicular to the axis its length is sqrt(H^2 + c^2 r^2) =
/// sqrt(H^2 q^2 + w^2 (R - r0)^2 r^2) / q: that root is taken from r^2, beside r's own, and
/// 1/q (for r/q and c) and q / root (1 / the length) are two divisions. One division,
/// 1 / (q root), gave both, but chained root, product, division and products one after another,
/// and a swarm loop over a block in L1 measured slower that way: the out-of-order core had
/// less to do while it waited.
/// `kPull` false leaves out the pull's arithmetic (its division among it) for a kernel whose
/// pull is zero, where it adds nothing: the same force.
/// `radius`: with kAir, a ball of that radius in air with a density feels the air by its size.
template <DryerAxis kAxis = DryerAxis::Any, bool kAir = false, class T, bool kPull = kAir>
inline Vec3<T> blowDryerForce(const BlowDryerKernelT<T>& f, const Vec3<T>& x, const Vec3<T>& v = Vec3<T>(T(0)),
                              T radius = T(0))
{
    constexpr bool kUp = kAxis == DryerAxis::Up;
    const auto [d, h, rho, r2, across2] = DryerFrameT<kAxis, T>(f.nozzle, f.axis, x);
    const T r = std::sqrt(r2);
    const T s = h * f.inverseHeight;
    const T radiusHere = f.nozzleRadius + f.spread * s;
    // Selects rather than branches: the same arithmetic for every particle (a vectorised loop
    // turns them into masked moves, cheaper than multiplying by masks as numbers).
    const bool inShaft = inBlowDryerShaft(f, d.y, across2);
    // A tilted cone may reach below the floor: there the shaft's air wins (an upward axis keeps
    // the two apart by h's sign alone).
    const bool inside = (h >= T(0)) & (s < T(1)) & (r < radiusHere) & (kUp | !inShaft);
    // Computed for every particle, as if inside: outside, q may be zero or negative and what
    // follows infinite or NaN, but only the selects below read it (no traps are enabled).
    // Selecting q itself instead made GCC compute the roots and the division twice, once per
    // value of q.
    const T q = radiusHere;
    const T root = std::sqrt(f.height * f.height * q * q + f.flowSpread * f.flowSpread * r2); // q |flow|
    const T inverseRadius = T(1) / q;
    const T inverseLength = q / root; // 1 / |flow|
    // Inside the cone both falloffs' arguments lie in (0, 1]: no clamps.
    const T u = T(1) - r * inverseRadius;
    const T magnitude = f.axial.inRange(T(1) - s) * f.radial.inRange(u);
    // Vertical: the axis. Cone-flow: H axis + (R - r0) rho / R(h). In the shaft: the axis.
    // `inside` excludes the shaft, so the cone's push or the shaft's, whichever applies, is one
    // select (written as the shaft's select of the cone's, GCC made it three and four mask
    // operations).
    const T scale = magnitude * inverseLength;
    const T along = inside ? scale * f.height : inShaft ? f.shaftPush : T(0);
    T radial = inside ? scale * f.flowSpread * inverseRadius : T(0);
    Vec3<T> extra(T(0));
    // The pull over rho: beta U^2 w dw/dr / r, with w = A(1 - s) Rf(u) and dw/dr = -A(1 - s) Rf'(u) / q.
    const auto pullPerR = [&](T betaU2) {
        const T a = f.axialProfile.inRange(T(1) - s);
        const T perR = betaU2 * a * a * f.radial.inRange(u) * f.radial.slope(u) * inverseRadius / r;
        return (inside & (r > T(0))) ? perR : T(0);
    };
    if constexpr (kAir) {
        if (f.movesBall(radius)) {
            // The push turned into the air's velocity; the ball feels it on its cross-section, where
            // the air blows (the room's still air is the `drag` force's).
            constexpr T kPi = T(3.14159265358979323846);
            const Vec3<T> relative = dryerForceFrom<kAxis, false>(f, along, radial, d, rho, extra) * f.airPerPush - v;
            const T area = (inside | inShaft) ? kPi * radius * radius : T(0);
            const T drag = f.dragPerArea * area * glm::length(relative);
            const T volume = T(4) / T(3) * kPi * radius * radius * radius;
            return drag * relative - pullPerR(f.pullPerVolume * volume) * rho;
        }
    }
    if constexpr (kPull)
        radial -= pullPerR(f.pull);
    if constexpr (kAir) {
        // The air drag's velocity term, where the air blows (its push is the force above).
        const T drag = (inside | inShaft) ? f.airDrag : T(0);
        extra = -drag * v;
    }
    return dryerForceFrom<kAxis, kAir>(f, along, radial, d, rho, extra);
}

/// A cheap superset (no root, no division) of where blowDryerForce's force can be other than a
/// zero vector: its cone (`inside`) or its shaft. The cone's test compares squares
/// with a margin: r < q for r the rounded root of r^2 means r^2 < q^2 exactly, and the rounded
/// q q 1.001 (plus a normal float, for a q whose square underflows) exceeds q^2.
template <DryerAxis kAxis = DryerAxis::Any, class T>
inline bool blowDryerMayPush(const BlowDryerKernelT<T>& f, const Vec3<T>& x)
{
    const auto [d, h, rho, r2, across2] = DryerFrameT<kAxis, T>(f.nozzle, f.axis, x);
    const T s = h * f.inverseHeight;
    const T q = f.nozzleRadius + f.spread * s;
    const bool inShaft = inBlowDryerShaft(f, d.y, across2);
    return inShaft | ((h >= T(0)) & (s < T(1)) & (r2 < q * q * T(1.001) + T(1e-30)));
}

/// The cone and the shaft of blowDryerMayPush grown by a particle's reach over one step of an
/// integrator that evaluates the force at several points (velocity Verlet, RK4), so that one
/// test at the step's start (blowDryerMayPushWithin) answers for them all: a swarm's loop away
/// from the dryer made four tests a particle for RK4, two for velocity Verlet.
///
/// The reach, by induction over the stages. While every point evaluated so far has been away
/// from the dryer, the acceleration there is gravity plus drag, of length at most
/// A = |g| + c W for stage velocities of length at most W. Velocity Verlet evaluates at x and
/// x + v dt + a0 dt^2 / 2 (then at the velocity v + a0 dt); RK4 at x, x + v dt / 2,
/// x + k2x dt / 2 and x + k3x dt, with k2x, k3x and k4x within A dt of v. So W <= |v| + A dt,
/// A <= (|g| + c |v|) / (1 - c dt), and every point lies within |v| dt + A dt^2 of x:
/// e = atRest + perSpeed |v|_1 (|v|_1 >= |v|, no root). The geometry: a point p within e of x
/// that blowDryerMayPush takes for the cone has 0 <= h_p < H and r_p < q(h_p) (to its margin),
/// so x has -e < h < H + e and r < r_p + e < q(h) + |R - r0| e / H + e; for the shaft,
/// h < e and r < r0 + e. Each bound carries 1% more and an absolute slack of 1e-5 of the
/// dryer's size and position, far above either test's roundings.
template <class T>
struct BlowDryerReachT {
    Vec3<T> nozzle, axis;
    T atRest, perSpeed;                 ///< the reach e = atRest + perSpeed |v|_1
    T coneTop, coneRadius, coneSlope;   ///< 1.01 H, 1.01 r0, 1.01 (R - r0) / H
    T widening;                         ///< 1 + 1.01 |R - r0| / H: the cone's radius grows by it times e
    T shaftRadius, shaftOn;             ///< 1.01 r0 and 1 with a shaft; 0 and 0 without

    /// For a step of dt with gravity of length `gravity` and linear drag `drag` (over the mass).
    /// A drag of c dt >= 1 (no bound) makes every particle's reach infinite.
    BlowDryerReachT(const BlowDryerKernelT<T>& f, double dt, double gravity, double drag)
        : nozzle(f.nozzle), axis(f.axis), coneTop(T(1.01) * f.height), coneRadius(T(1.01) * f.nozzleRadius),
          coneSlope(T(1.01) * f.spread * f.inverseHeight),
          widening(T(1) + T(1.01) * std::abs(f.spread) * f.inverseHeight),
          shaftRadius(f.shaftRadius2 > T(0) ? T(1.01) * f.nozzleRadius : T(0)),
          shaftOn(f.shaftRadius2 > T(0) ? T(1) : T(0))
    {
        const double c = std::abs(drag), free = 1.0 - c * dt;
        const double size = 1.0 + 2.0 * std::max({std::abs(double(f.nozzle.x)), std::abs(double(f.nozzle.y)),
                                                  std::abs(double(f.nozzle.z))}) +
                            double(f.height) + double(f.nozzleRadius) + std::abs(double(f.spread));
        const double rest = 1.01 * std::abs(gravity) * dt * dt / free + 1e-5 * size;
        const double speed = 1.01 * (dt + c * dt * dt / free);
        const bool bounded = free > 0.0 && std::isfinite(rest) && std::isfinite(speed);
        atRest = bounded ? T(rest) : std::numeric_limits<T>::infinity();
        perSpeed = bounded ? T(speed) : T(0);
    }
};
using BlowDryerReach = BlowDryerReachT<float>;

/// Whether blowDryerMayPush may be true at any point an integrator's step from x at velocity v
/// evaluates the force at, while the points before it were away from the dryer (see
/// BlowDryerReachT): false means the step is the one the acceleration without the dryer gives
/// (its force is a zero vector at every point; a swarm's withoutDryer). About thirty
/// operations, against seventeen for each point blowDryerMayPush tests.
template <DryerAxis kAxis = DryerAxis::Any, class T>
inline bool blowDryerMayPushWithin(const BlowDryerReachT<T>& f, const Vec3<T>& x, const Vec3<T>& v)
{
    const T e = f.atRest + f.perSpeed * (std::abs(v.x) + std::abs(v.y) + std::abs(v.z));
    const auto [d, h, rho, r2, across2] = DryerFrameT<kAxis, T>(f.nozzle, f.axis, x);
    const T shaft = f.shaftRadius + f.shaftOn * e;
    const bool inShaft = (d.y < e) & (across2 < shaft * shaft);
    const T q = std::max(f.coneRadius + f.coneSlope * h, T(0)) + f.widening * e;
    return inShaft | ((h > -e) & (h < f.coneTop + e) & (r2 < q * q));
}

} // namespace pba
