#pragma once
// The time of impact of one integrator step with a plane: where the exact response stops a
// body's step to bounce it. Private to the core (see pba/collision.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "pba/collision.hpp"
#include "pba/integrator.hpp"

namespace pba::collision_detail {

/// Smallest tau in (0, limit] where c0 + c1 tau + c2 tau^2 falls through zero, with c0 >= 0.
/// Uses the cancellation-free form of the quadratic formula.
template <class T>
inline std::optional<T> firstQuadraticCrossing(T c0, T c1, T c2, T limit)
{
    if (c0 <= T(0) && c1 < T(0))
        return T(0); // on the surface and moving in: impact now
    std::optional<T> best;
    auto consider = [&](T r) {
        if (r > T(0) && r <= limit && (!best || r < *best))
            best = r;
    };
    if (c2 == T(0)) {
        if (c1 < T(0))
            consider(-c0 / c1);
        return best;
    }
    const T disc = c1 * c1 - T(4) * c2 * c0;
    if (disc < T(0))
        return best;
    const T q = T(-0.5) * (c1 + std::copysign(std::sqrt(disc), c1));
    if (q != T(0)) {
        consider(q / c2);
        consider(c0 / q);
    }
    // Only a crossing from inside to outside counts: the slope there must be negative.
    if (best && c1 + T(2) * c2 * *best > T(0))
        return std::nullopt;
    return best;
}

/// Signed distance after one integrator step of length tau from (x, v).
template <class T, class Accel>
inline T distanceAfter(Integrator integrator, const PlaneT<T>& plane, Vec3<T> x, Vec3<T> v, T tau, Accel&& accel)
{
    integrate(integrator, x, v, tau, accel);
    return plane.distance(x);
}

/// The time of impact of one integrator step with a plane, or nothing if the step stays inside.
/// Forward Euler, semi-implicit Euler and velocity Verlet move the position along a polynomial
/// in tau built from the start-of-step acceleration, so their impact time is closed form.
/// RK4's path is a polynomial only for constant forces: it is bracketed and bisected on the
/// real RK4 step, which converges to the same root (to rounding) when the forces are constant.
template <class T, class Accel>
inline std::optional<T> timeOfImpact(Integrator integrator, const PlaneT<T>& plane, const Vec3<T>& x,
                                     const Vec3<T>& v, T limit, Accel&& accel)
{
    const T c0 = std::max(plane.distance(x), T(0));
    const T c1 = glm::dot(plane.normal, v);
    const T an = glm::dot(plane.normal, accel(x, v));
    switch (integrator) {
    case Integrator::ForwardEuler: return firstQuadraticCrossing(c0, c1, T(0), limit);
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitGyroscopic:
    case Integrator::ImplicitEuler: // stepped as a system (reflect); alone, semi-implicit Euler
    case Integrator::Xpbd: return firstQuadraticCrossing(c0, c1, an, limit);
    case Integrator::VelocityVerlet:
    case Integrator::Splitting: return firstQuadraticCrossing(c0, c1, T(0.5) * an, limit);
    case Integrator::RK4: break;
    }
    // RK4: the constant-acceleration estimate and a few samples find the first sign change.
    constexpr int kSamples = 8;
    const std::optional<T> estimate = firstQuadraticCrossing(c0, c1, T(0.5) * an, limit);
    if (estimate && *estimate == T(0))
        return estimate;
    if (!estimate && distanceAfter(integrator, plane, x, v, limit, accel) >= T(0))
        return std::nullopt;
    std::array<T, kSamples + 1> taus{};
    std::size_t count = 0;
    for (int k = 1; k <= kSamples; ++k)
        taus[count++] = limit * T(k) / T(kSamples);
    if (estimate)
        taus[count++] = *estimate;
    std::sort(taus.begin(), taus.begin() + count);
    T lo = T(0);
    T hi = limit;
    bool found = false;
    for (std::size_t i = 0; i < count && !found; ++i) {
        if (distanceAfter(integrator, plane, x, v, taus[i], accel) < T(0)) {
            hi = taus[i];
            found = true;
        } else {
            lo = taus[i];
        }
    }
    if (!found)
        return std::nullopt;
    for (int i = 0; i < 200 && lo < hi; ++i) {
        const T mid = lo + (hi - lo) * T(0.5);
        if (mid <= lo || mid >= hi)
            break;
        (distanceAfter(integrator, plane, x, v, mid, accel) < T(0) ? hi : lo) = mid;
    }
    return hi;
}

/// timeOfImpact for a plane that may have a hole: a body already in the shaft below the hole
/// does not meet the plane, and neither does one whose path crosses it over the hole.
template <class T, class Accel>
inline std::optional<T> timeOfImpactWithHole(Integrator integrator, const PlaneT<T>& plane, const Vec3<T>& x,
                                             const Vec3<T>& v, T limit, Accel&& accel)
{
    if (plane.holeRadius <= T(0))
        return timeOfImpact(integrator, plane, x, v, limit, accel);
    if (plane.distance(x) < T(0) && plane.overHole(x))
        return std::nullopt;
    const std::optional<T> tau = timeOfImpact(integrator, plane, x, v, limit, accel);
    if (!tau)
        return tau;
    Vec3<T> xi = x;
    Vec3<T> vi = v;
    integrate(integrator, xi, vi, *tau, accel);
    return plane.overHole(xi) ? std::nullopt : tau;
}

} // namespace pba::collision_detail
