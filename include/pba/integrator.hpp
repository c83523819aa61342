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
#include <span>
#include <string>
#include <string_view>

#include "pba/math.hpp"

namespace pba {

/// The methods a body may name. The first four are explicit and move anything the same way:
/// a particle, a swarm, a coupled system, a rigid body (translation and rotation alike).
///  - ImplicitGyroscopic is semi-implicit Euler whose rotation takes the implicit gyroscopic step
///    (rotation.hpp): it differs from SemiImplicitEuler only for a body that turns.
///  - Splitting is velocity Verlet whose rotation takes a symplectic splitting of the free rigid
///    body (rotation.hpp): it keeps |L| to rounding and the energy bounded; for a particle it is
///    velocity Verlet.
///  - ImplicitEuler (backward Euler, linearised once a step, implicit in the springs) and Xpbd
///    (the springs as constraints of compliance 1/k, in substeps) step particles joined by springs
///    as one system (the World's integrateBackwardEuler and integrateXpbd): ropes, cloth, a
///    particle on a spring. A rigid body or a swarm cannot take them.
enum class Integrator { ForwardEuler, SemiImplicitEuler, VelocityVerlet, RK4, ImplicitGyroscopic, Splitting,
                        ImplicitEuler, Xpbd };

/// The four explicit methods of the integrator study: what moves a point (a particle, a swarm).
inline constexpr std::array<Integrator, 4> kAllIntegrators{
    Integrator::ForwardEuler, Integrator::SemiImplicitEuler, Integrator::VelocityVerlet, Integrator::RK4};
/// The methods that move particles differently (the particle study's): the four, and the two that
/// step springs implicitly. Each is one system of the World's coupled bodies.
inline constexpr std::array<Integrator, 6> kParticleIntegrators{
    Integrator::ForwardEuler, Integrator::SemiImplicitEuler, Integrator::VelocityVerlet, Integrator::RK4,
    Integrator::ImplicitEuler, Integrator::Xpbd};
/// The methods a rigid body may take (the rotation study's): the four, and the two that treat its
/// rotation on their own.
inline constexpr std::array<Integrator, 6> kRigidIntegrators{
    Integrator::ForwardEuler, Integrator::SemiImplicitEuler, Integrator::VelocityVerlet, Integrator::RK4,
    Integrator::ImplicitGyroscopic, Integrator::Splitting};
/// Every method a body may name.
inline constexpr std::array<Integrator, 8> kEveryIntegrator{
    Integrator::ForwardEuler, Integrator::SemiImplicitEuler, Integrator::VelocityVerlet, Integrator::RK4,
    Integrator::ImplicitGyroscopic, Integrator::Splitting, Integrator::ImplicitEuler, Integrator::Xpbd};

/// The method that moves a point: ImplicitGyroscopic's translation is semi-implicit Euler and
/// Splitting's velocity Verlet; the others are their own.
constexpr Integrator translationalMethod(Integrator integrator)
{
    switch (integrator) {
    case Integrator::ImplicitGyroscopic: return Integrator::SemiImplicitEuler;
    case Integrator::Splitting: return Integrator::VelocityVerlet;
    default: return integrator;
    }
}

/// Whether the method steps particles joined by springs as one implicit system (ImplicitEuler,
/// Xpbd): never a rigid body or a swarm.
constexpr bool isSpringSystemMethod(Integrator integrator)
{
    return integrator == Integrator::ImplicitEuler || integrator == Integrator::Xpbd;
}

/// Scene and command-line name: "forward-euler", "semi-implicit-euler", "velocity-verlet", "rk4",
/// "implicit-gyroscopic", "splitting", "implicit-euler", "xpbd".
std::string_view integratorName(Integrator integrator);
std::optional<Integrator> integratorFromName(std::string_view name);
/// Every name integratorFromName takes, as an error lists them: "forward-euler, ..., implicit-euler
/// or xpbd".
std::string integratorNameList();
/// Global order of accuracy: 1, 1, 2, 4, 1, 2, 1, 1 (XPBD's in the substep, dt / substeps).
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

/// The weight of each of the method's evaluations of accel, in the order integrate() makes them,
/// in its change of velocity: v(t+dt) - v(t) = dt sum_k w_k a_k, exactly. So a force's share of
/// the step's kinetic energy change is dt sum_k w_k F_k . (v(t) + v(t+dt)) / 2 (the blow-up
/// watch's work of an energy source).
inline std::span<const double> stageWeights(Integrator integrator)
{
    static constexpr std::array<double, 1> one{1.0};
    static constexpr std::array<double, 2> verlet{0.5, 0.5};
    static constexpr std::array<double, 4> rk{1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
    switch (translationalMethod(integrator)) {
    case Integrator::VelocityVerlet: return verlet;
    case Integrator::RK4: return rk;
    default: return one; // (forward and semi-implicit Euler, and a point with no spring on a spring method)
    }
}

/// One step of the named integrator.
template <class X, class T, class Accel>
inline void integrate(Integrator integrator, X& x, X& v, T dt, Accel&& accel)
{
    switch (integrator) {
    case Integrator::ForwardEuler: forwardEuler(x, v, dt, accel); return;
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitGyroscopic:
    // The World steps the spring systems' methods itself; a point with no spring, its forces all
    // taken at the start, moves by them as by semi-implicit Euler.
    case Integrator::ImplicitEuler:
    case Integrator::Xpbd: semiImplicitEuler(x, v, dt, accel); return;
    case Integrator::VelocityVerlet:
    case Integrator::Splitting: velocityVerlet(x, v, dt, accel); return;
    case Integrator::RK4: rk4(x, v, dt, accel); return;
    }
}

} // namespace pba
