#pragma once
// The rotational equations of a rigid body and their integrators, as integrator.hpp holds the
// translational ones. The state is the orientation q (a unit quaternion, body to world) and the
// angular momentum L in the world frame; from them the angular velocity
//     omega = R I_body^-1 R^T L        (R the rotation matrix of q)
// and the equations
//     dq/dt = 1/2 (0, omega) q,        dL/dt = tau(q, L).
// L rather than omega is the state because it is what a torque changes and what stays constant
// without one: Euler's equations, with their gyroscopic term I_w' omega, follow from it. Every
// method renormalises q at the end of its step.
#include <glm/gtc/quaternion.hpp>

#include "pba/integrator.hpp"
#include "pba/math.hpp"

namespace pba {

using glm::dquat;

/// A rigid body's rotational state.
struct Rotation {
    dquat orientation{1.0, 0.0, 0.0, 0.0}; ///< body to world, unit (w, x, y, z)
    dvec3 momentum{0.0};                   ///< angular momentum L, world frame, kg m^2/s
};

/// omega = R I_body^-1 R^T L, the world-frame angular velocity.
inline dvec3 angularVelocity(const dquat& q, const dmat3& inverseInertiaBody, const dvec3& momentum)
{
    const dmat3 r = glm::mat3_cast(q);
    return r * (inverseInertiaBody * (glm::transpose(r) * momentum));
}

/// dq/dt = 1/2 (0, omega) q.
inline dquat orientationRate(const dquat& q, const dvec3& omega)
{
    return dquat(0.0, omega.x, omega.y, omega.z) * q * 0.5;
}

/// One step of the rotational equations with the named integrator, the torque (world frame)
/// `torque(q, L)` evaluated at the method's stages as the forces are. The methods mirror the
/// translational ones: forward Euler moves q with the start's omega; semi-implicit Euler first
/// changes L, then moves q with the omega of the new L; velocity Verlet kicks L by half a step,
/// drifts q by the midpoint rule with that L, and kicks again (second order); RK4 is the
/// classic method on (q, L).
template <class Torque>
inline void integrateRotation(Integrator integrator, Rotation& s, const dmat3& inverseInertiaBody, double dt,
                              Torque&& torque)
{
    const auto rate = [&](const dquat& q, const dvec3& l) {
        return orientationRate(q, angularVelocity(q, inverseInertiaBody, l));
    };
    dquat& q = s.orientation;
    dvec3& l = s.momentum;
    switch (integrator) {
    case Integrator::ForwardEuler: {
        const dvec3 tau = torque(q, l);
        q = q + rate(q, l) * dt;
        l += tau * dt;
        break;
    }
    case Integrator::SemiImplicitEuler:
        l += torque(q, l) * dt;
        q = q + rate(q, l) * dt;
        break;
    case Integrator::VelocityVerlet: {
        const dvec3 half = l + torque(q, l) * (0.5 * dt);
        const dquat mid = glm::normalize(q + rate(q, half) * (0.5 * dt));
        q = q + rate(mid, half) * dt;
        l = half + torque(glm::normalize(q), half) * (0.5 * dt);
        break;
    }
    case Integrator::RK4: {
        const dquat q1 = rate(q, l);
        const dvec3 l1 = torque(q, l);
        const dquat q2 = rate(q + q1 * (0.5 * dt), l + l1 * (0.5 * dt));
        const dvec3 l2 = torque(q + q1 * (0.5 * dt), l + l1 * (0.5 * dt));
        const dquat q3 = rate(q + q2 * (0.5 * dt), l + l2 * (0.5 * dt));
        const dvec3 l3 = torque(q + q2 * (0.5 * dt), l + l2 * (0.5 * dt));
        const dquat q4 = rate(q + q3 * dt, l + l3 * dt);
        const dvec3 l4 = torque(q + q3 * dt, l + l3 * dt);
        q = q + (q1 + (q2 + q3) * 2.0 + q4) * (dt / 6.0);
        l += (l1 + (l2 + l3) * 2.0 + l4) * (dt / 6.0);
        break;
    }
    }
    q = glm::normalize(q);
}

/// The implicit gyroscopic step (Catto, GDC 2015; Bullet's btRigidBody::computeGyroscopicImpulseImplicit_Body):
/// the torque is applied explicitly, then the body-frame equation I (w1 - w0) + dt w1 x I w1 = 0
/// is solved for w1 by one Newton iteration from w0, and q moves with w1 (semi-implicit).
/// Explicit methods gain energy on a fast-spinning asymmetric body at a large dt; this one
/// stays bounded (it loses a little), which is why game engines use it.
inline void implicitGyroscopicStep(Rotation& s, const dmat3& inertiaBody, const dmat3& inverseInertiaBody,
                                   const dvec3& torqueWorld, double dt)
{
    const dmat3 r = glm::mat3_cast(s.orientation);
    const dmat3 rt = glm::transpose(r);
    const dvec3 l = s.momentum + torqueWorld * dt;
    const dvec3 w0 = inverseInertiaBody * (rt * l); // body frame
    const dvec3 iw = inertiaBody * w0;
    const dvec3 f = dt * glm::cross(w0, iw);
    // J = I + dt (skew(w) I - skew(I w)), with skew(a) b = a x b.
    auto skew = [](const dvec3& a) { return dmat3(0.0, a.z, -a.y, -a.z, 0.0, a.x, a.y, -a.x, 0.0); };
    const dmat3 j = inertiaBody + dt * (skew(w0) * inertiaBody - skew(iw));
    const dvec3 w1 = w0 - glm::inverse(j) * f;
    // The step's result is the angular velocity (world frame), as Bullet and Box2D keep it: the
    // orientation moves with it, and L is what that velocity is at the new orientation.
    const dvec3 omega = r * w1;
    s.orientation = glm::normalize(s.orientation + orientationRate(s.orientation, omega) * dt);
    const dmat3 r1 = glm::mat3_cast(s.orientation);
    s.momentum = r1 * (inertiaBody * (glm::transpose(r1) * omega));
}

} // namespace pba
