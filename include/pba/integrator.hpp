#pragma once
// The integrators, one implementation each. They are templates over the state type
// (a Vec3<T>, or a Vec3Array holding a whole coupled group), the scalar type and the
// acceleration function, so the same code steps a single double-precision Particle, a
// group of bodies joined by springs as one system, and, inlined into a loop, a float swarm.
//
// `accel(x, v)` returns the acceleration at a trial state (of every body of the group). Multi-stage methods
// call it at their intermediate states: forces may depend on position and
// velocity (springs, drag, the blow dryer), so reusing the start-of-step force
// would silently lower their order.
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "pba/math.hpp"

namespace pba {

/// ImplicitGyroscopic is semi-implicit Euler whose rotation takes the implicit gyroscopic step
/// (rotation.hpp): it differs from SemiImplicitEuler only for a body that turns.
enum class Integrator { ForwardEuler, SemiImplicitEuler, VelocityVerlet, RK4, ImplicitGyroscopic };

/// The four methods of the integrator study: what moves a point (a particle, a swarm).
inline constexpr std::array<Integrator, 4> kAllIntegrators{
    Integrator::ForwardEuler, Integrator::SemiImplicitEuler, Integrator::VelocityVerlet, Integrator::RK4};
/// Every method a body may name: the four, and the rigid bodies' fifth.
inline constexpr std::array<Integrator, 5> kEveryIntegrator{Integrator::ForwardEuler, Integrator::SemiImplicitEuler,
                                                            Integrator::VelocityVerlet, Integrator::RK4,
                                                            Integrator::ImplicitGyroscopic};

/// The method that moves a point: ImplicitGyroscopic's translation is semi-implicit Euler.
constexpr Integrator translationalMethod(Integrator integrator)
{
    return integrator == Integrator::ImplicitGyroscopic ? Integrator::SemiImplicitEuler : integrator;
}

/// Scene and command-line name: "forward-euler", "semi-implicit-euler", "velocity-verlet", "rk4",
/// "implicit-gyroscopic".
std::string_view integratorName(Integrator integrator);
std::optional<Integrator> integratorFromName(std::string_view name);
/// Every name integratorFromName takes, as an error lists them: "forward-euler, ..., rk4 or
/// implicit-gyroscopic".
std::string integratorNameList();
/// Global order of accuracy: 1, 1, 2, 4, 1.
int integratorOrder(Integrator integrator);

/// x(t+dt) = x + v dt, v(t+dt) = v + a(x, v) dt. First order; gains energy on oscillators.
template <class X, class T, class Accel>
inline void forwardEuler(X& x, X& v, T dt, Accel&& accel)
{
    const X a = accel(x, v);
    x += v * dt;
    v += a * dt;
}

/// Symplectic (semi-implicit) Euler: the velocity first, then the position with the new velocity.
/// First order, but it conserves a shadow energy, so oscillation energy stays bounded.
template <class X, class T, class Accel>
inline void semiImplicitEuler(X& x, X& v, T dt, Accel&& accel)
{
    v += accel(x, v) * dt;
    x += v * dt;
}

/// Velocity Verlet: x += v dt + a dt^2 / 2, then v += (a0 + a1) dt / 2. Second order,
/// symplectic for position-only forces; the end acceleration is taken at the predicted
/// velocity v + a0 dt so velocity-dependent forces remain usable.
template <class X, class T, class Accel>
inline void velocityVerlet(X& x, X& v, T dt, Accel&& accel)
{
    const T half = T(0.5);
    const X a0 = accel(x, v);
    // x moves first and a1 is taken there: no copy of the new position to assign afterwards,
    // which in a large inlined swarm loop GCC kept in memory and so stopped vectorising.
    x = x + v * dt + a0 * (half * dt * dt);
    const X a1 = accel(x, v + a0 * dt);
    v += (a0 + a1) * (half * dt);
}

/// Classic fourth-order Runge-Kutta on the first-order system (x' = v, v' = a(x, v)).
template <class X, class T, class Accel>
inline void rk4(X& x, X& v, T dt, Accel&& accel)
{
    const T half = T(0.5) * dt;
    const T sixth = dt / T(6);
    const X k1x = v;
    const X k1v = accel(x, v);
    const X k2x = v + k1v * half;
    const X k2v = accel(x + k1x * half, k2x);
    const X k3x = v + k2v * half;
    const X k3v = accel(x + k2x * half, k3x);
    const X k4x = v + k3v * dt;
    const X k4v = accel(x + k3x * dt, k4x);
    x += (k1x + T(2) * (k2x + k3x) + k4x) * sixth;
    v += (k1v + T(2) * (k2v + k3v) + k4v) * sixth;
}

/// One step of the named integrator.
template <class X, class T, class Accel>
inline void integrate(Integrator integrator, X& x, X& v, T dt, Accel&& accel)
{
    switch (integrator) {
    case Integrator::ForwardEuler: forwardEuler(x, v, dt, accel); return;
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitGyroscopic: semiImplicitEuler(x, v, dt, accel); return;
    case Integrator::VelocityVerlet: velocityVerlet(x, v, dt, accel); return;
    case Integrator::RK4: rk4(x, v, dt, accel); return;
    }
}

} // namespace pba
