#pragma once
// The rotational equations of a rigid body and their integrators, as integrator.hpp holds the
// translational ones. The state is the orientation q (a unit quaternion, body to world) and the
// angular momentum L in the world frame; from them the angular velocity
//     omega = R I_body^-1 R^T L        (R the rotation matrix of q)
// and the equations
//     dq/dt = 1/2 (0, omega) q,        dL/dt = tau(q, L).
// L rather than omega is the state because it is what a torque changes and what stays constant
// without one: Euler's equations, with their gyroscopic term I_w' omega, follow from it. Every
// method renormalises q at the end of its step. This header declares; the stages of each method
// are in pba/detail/rigid_step.hpp (templates, included at the end), the rotations' own steps in
// src/core/bodies/rotation.cpp.
#include <span>
#include <vector>

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

/// A rigid body's whole state as the integrators move it: the translation's (x, v) and the
/// rotation's (q, L).
struct RigidState {
    dvec3 x{0.0};
    dvec3 v{0.0};
    Rotation rotation;
};

/// What the forces do to a body at a stage: the force through its centre of mass and the torque
/// about it (world frame).
struct Wrench {
    dvec3 force{0.0};
    dvec3 torque{0.0};
};

/// What a body's motion needs of its mass.
struct RigidInertia {
    double inverseMass = 1.0;
    dmat3 inertiaBody{1.0};
    dmat3 inverseInertiaBody{1.0};
};

/// The implicit gyroscopic step (Catto, GDC 2015; Bullet's btRigidBody::computeGyroscopicImpulseImplicit_Body):
/// the torque is applied explicitly, then the body-frame equation I (w1 - w0) + dt w1 x I w1 = 0
/// is solved for w1 by one Newton iteration from w0, and q moves with w1 (semi-implicit).
/// Explicit methods gain energy on a fast-spinning asymmetric body at a large dt; this one
/// stays bounded because it loses energy (it dissipates spin), which is why game engines use it.
void implicitGyroscopicStep(Rotation& s, const dmat3& inertiaBody, const dmat3& inverseInertiaBody,
                            const dvec3& torqueWorld, double dt);

/// The free rigid body's flow over dt as the splitting integrator takes it (McLachlan 1993;
/// Dullweber, Leimkuhler and McLachlan 1997): the kinetic energy T = sum L_i^2 / (2 I_i) (L_i
/// about the principal axes) is split into its three terms, the flow of each one is exact (a turn
/// about its own principal axis by dt L_i / I_i, which leaves L_i as it is), and the flows are
/// composed symmetrically, T_a(dt/2) T_b(dt/2) T_c(dt) T_b(dt/2) T_a(dt/2). Each flow is a
/// rotation that leaves L fixed in space, so L is not touched and |L| is kept exactly; the
/// composition is symplectic and time-reversible, of second order, so its energy error stays
/// bounded (a modified energy is kept) over any run, at a dt where the explicit methods gain
/// energy without end. Returns q turned by the flow (unit). An inertia tensor that is not
/// diagonal in the body's frame (a mesh's) is diagonalised first.
dquat freeRotation(const dquat& q, const dvec3& momentum, const dmat3& inertiaBody, double dt);

namespace rigid_detail {

/// A derivative of a RigidState: x' = v, v' = F/m, q' = 1/2 (0, omega) q, L' = tau.
struct Derivative {
    dvec3 dx, dv;
    dquat dq;
    dvec3 dl;
};

} // namespace rigid_detail

/// stepRigidSystem's default `forEach`: every body in order, on the calling thread.
struct InOrder {
    template <class F>
    void operator()(std::size_t n, F&& fn) const
    {
        for (std::size_t k = 0; k < n; ++k)
            fn(k);
    }
};

/// The stepper's working arrays: a caller that steps many bodies every frame keeps one and
/// passes it, so that a step allocates nothing.
struct RigidStepBuffers {
    std::vector<Wrench> w, w0;
    std::vector<RigidState> start, stage, unit;
    std::vector<rigid_detail::Derivative> k1, k2, k3;
};

/// One step of the named integrator for a system of rigid bodies, translation and rotation
/// together: `wrenches(stage, out)` fills out[k] with the force and torque on body k at the
/// stage's states (every body's at once, so forces between them see one consistent stage, and
/// a force at a point couples a body's translation and rotation). The methods are the
/// translational ones (integrator.hpp) applied to (x, q; v, L):
///  - forward Euler moves x and q with the start's v and omega;
///  - semi-implicit Euler first changes v and L, then moves x and q with the new ones;
///  - velocity Verlet drifts x with the start's acceleration and q by the midpoint rule with L
///    kicked by half a step, evaluates there (at the predicted v and L), and kicks again;
///  - splitting is velocity Verlet whose drift of q is the free rigid body's own flow
///    (freeRotation) at the half-kicked L: kick, drift, kick. Without a torque L never changes,
///    and with conservative ones the step is symplectic (the splitting of the free body composed
///    with the kicks);
///  - RK4 is the classic method on the whole state;
///  - implicit-gyroscopic is semi-implicit Euler with the rotation's implicit gyroscopic step.
/// q is renormalised at the end of every step; the stages a force sees have unit q. `forEach(n,
/// fn)` runs fn(k) for every body k < n: in order by default, or spread over cores by a caller
/// whose bodies are many (each body's arithmetic is its own, so the result is the same).
/// implicit-euler and xpbd step particles joined by springs, not rigid bodies: given one, the
/// step throws std::invalid_argument before moving anything.
template <class Wrenches, class ForEach = InOrder>
void stepRigidSystem(Integrator integrator, std::span<RigidState> states, std::span<const RigidInertia> inertia,
                     double dt, Wrenches&& wrenches, ForEach&& forEach = {}, RigidStepBuffers* buffers = nullptr);

/// One step of the rotational equations alone (a body with no translation to speak of), the
/// torque (world frame) `torque(q, L)` evaluated at the method's stages: stepRigidSystem for one
/// body that feels no force.
template <class Torque>
void integrateRotation(Integrator integrator, Rotation& s, const dmat3& inverseInertiaBody, double dt,
                       Torque&& torque);

} // namespace pba

// The templates' definitions: each method's stages.
#include "pba/detail/rigid_step.hpp"
