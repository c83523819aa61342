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

namespace rigid_detail {

/// dq/dt at a stage whose q is not exactly unit (RK4's and Verlet's intermediate stages): omega
/// from the normalised orientation, applied to q itself.
inline dquat rate(const dquat& q, const dmat3& inverseInertiaBody, const dvec3& momentum)
{
    return orientationRate(q, angularVelocity(glm::normalize(q), inverseInertiaBody, momentum));
}

/// s + h * (the derivative whose rates are d): x' = v_d, v' = F/m, q' = rate, L' = tau.
struct Derivative {
    dvec3 dx, dv;
    dquat dq;
    dvec3 dl;
};

inline Derivative derivative(const RigidState& s, const Wrench& w, const RigidInertia& m)
{
    return {s.v, w.force * m.inverseMass, rate(s.rotation.orientation, m.inverseInertiaBody, s.rotation.momentum),
            w.torque};
}

inline RigidState advance(const RigidState& s, const Derivative& d, double h)
{
    return {s.x + d.dx * h, s.v + d.dv * h, Rotation{s.rotation.orientation + d.dq * h, s.rotation.momentum + d.dl * h}};
}

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

namespace rigid_detail {

/// stepRigidSystem's velocity Verlet, from the start's wrenches in b.w (see there).
template <class Evaluate, class ForEach>
void velocityVerletStages(RigidStepBuffers& b, std::span<RigidState> states, std::span<const RigidInertia> inertia,
                          double dt, Evaluate&& evaluate, ForEach&& forEach)
{
    const std::size_t n = states.size();
    auto& w = b.w;
    auto& w0 = b.w0;
    auto& start = b.start;
    auto& stage = b.stage;
    w0 = w;
    forEach(n, [&](std::size_t k) {
        const RigidState& s0 = start[k];
        const dvec3 a0 = w0[k].force * inertia[k].inverseMass;
        const dvec3 half = s0.rotation.momentum + w0[k].torque * (0.5 * dt);
        const dquat& q0 = s0.rotation.orientation;
        const dquat mid = glm::normalize(q0 + rate(q0, inertia[k].inverseInertiaBody, half) * (0.5 * dt));
        stage[k] = {s0.x + s0.v * dt + a0 * (0.5 * dt * dt), s0.v + a0 * dt,
                    Rotation{q0 + rate(mid, inertia[k].inverseInertiaBody, half) * dt,
                             s0.rotation.momentum + w0[k].torque * dt}};
    });
    evaluate(stage);
    forEach(n, [&](std::size_t k) {
        const RigidState& s0 = start[k];
        states[k] = {stage[k].x, s0.v + (w0[k].force + w[k].force) * (0.5 * dt * inertia[k].inverseMass),
                     Rotation{stage[k].rotation.orientation,
                              s0.rotation.momentum + (w0[k].torque + w[k].torque) * (0.5 * dt)}};
    });
}

/// stepRigidSystem's RK4, from the start's wrenches in b.w (see there).
template <class Evaluate, class ForEach>
void rk4Stages(RigidStepBuffers& b, std::span<RigidState> states, std::span<const RigidInertia> inertia, double dt,
               Evaluate&& evaluate, ForEach&& forEach)
{
    const std::size_t n = states.size();
    auto& w = b.w;
    auto& start = b.start;
    auto& stage = b.stage;
    auto& k1 = b.k1;
    auto& k2 = b.k2;
    auto& k3 = b.k3;
    k1.resize(n), k2.resize(n), k3.resize(n);
    forEach(n, [&](std::size_t k) {
        k1[k] = derivative(start[k], w[k], inertia[k]);
        stage[k] = advance(start[k], k1[k], 0.5 * dt);
    });
    evaluate(stage);
    forEach(n, [&](std::size_t k) {
        k2[k] = derivative(stage[k], w[k], inertia[k]);
        stage[k] = advance(start[k], k2[k], 0.5 * dt);
    });
    evaluate(stage);
    forEach(n, [&](std::size_t k) {
        k3[k] = derivative(stage[k], w[k], inertia[k]);
        stage[k] = advance(start[k], k3[k], dt);
    });
    evaluate(stage);
    forEach(n, [&](std::size_t k) {
        const Derivative k4 = derivative(stage[k], w[k], inertia[k]);
        const Derivative sum{k1[k].dx + (k2[k].dx + k3[k].dx) * 2.0 + k4.dx, k1[k].dv + (k2[k].dv + k3[k].dv) * 2.0 + k4.dv,
                             k1[k].dq + (k2[k].dq + k3[k].dq) * 2.0 + k4.dq, k1[k].dl + (k2[k].dl + k3[k].dl) * 2.0 + k4.dl};
        states[k] = advance(start[k], sum, dt / 6.0);
    });
}

} // namespace rigid_detail

/// One step of the named integrator for a system of rigid bodies, translation and rotation
/// together: `wrenches(stage, out)` fills out[k] with the force and torque on body k at the
/// stage's states (every body's at once, so forces between them see one consistent stage, and
/// a force at a point couples a body's translation and rotation). The methods are the
/// translational ones (integrator.hpp) applied to (x, q; v, L):
///  - forward Euler moves x and q with the start's v and omega;
///  - semi-implicit Euler first changes v and L, then moves x and q with the new ones;
///  - velocity Verlet drifts x with the start's acceleration and q by the midpoint rule with L
///    kicked by half a step, evaluates there (at the predicted v and L), and kicks again;
///  - RK4 is the classic method on the whole state;
///  - implicit-gyroscopic is semi-implicit Euler with the rotation's implicit gyroscopic step.
/// q is renormalised at the end of every step; the stages a force sees have unit q. `forEach(n,
/// fn)` runs fn(k) for every body k < n: in order by default, or spread over cores by a caller
/// whose bodies are many (each body's arithmetic is its own, so the result is the same).
template <class Wrenches, class ForEach = InOrder>
inline void stepRigidSystem(Integrator integrator, std::span<RigidState> states, std::span<const RigidInertia> inertia,
                            double dt, Wrenches&& wrenches, ForEach&& forEach = {}, RigidStepBuffers* buffers = nullptr)
{
    using namespace rigid_detail;
    const std::size_t n = states.size();
    RigidStepBuffers own;
    RigidStepBuffers& b = buffers ? *buffers : own;
    // Named references rather than a structured binding: the lambdas below capture them (which
    // clang 14, the fuzz build's compiler, does not allow for bindings).
    auto& w = b.w;
    auto& start = b.start;
    auto& stage = b.stage;
    auto& unit = b.unit;
    w.resize(n);
    stage.resize(n);
    unit.resize(n);
    auto evaluate = [&](const std::vector<RigidState>& at) {
        forEach(n, [&](std::size_t k) {
            unit[k] = at[k];
            unit[k].rotation.orientation = glm::normalize(at[k].rotation.orientation);
        });
        wrenches(std::span<const RigidState>(unit), std::span<Wrench>(w));
    };
    start.assign(states.begin(), states.end());
    evaluate(start);
    switch (integrator) {
    case Integrator::ForwardEuler:
        forEach(n, [&](std::size_t k) { states[k] = advance(start[k], derivative(start[k], w[k], inertia[k]), dt); });
        break;
    case Integrator::SemiImplicitEuler:
        forEach(n, [&](std::size_t k) {
            RigidState& s = states[k];
            s.v += w[k].force * (inertia[k].inverseMass * dt);
            s.rotation.momentum += w[k].torque * dt;
            s.x += s.v * dt;
            s.rotation.orientation += rate(s.rotation.orientation, inertia[k].inverseInertiaBody, s.rotation.momentum) * dt;
        });
        break;
    case Integrator::ImplicitGyroscopic:
        forEach(n, [&](std::size_t k) {
            RigidState& s = states[k];
            s.v += w[k].force * (inertia[k].inverseMass * dt);
            s.x += s.v * dt;
            implicitGyroscopicStep(s.rotation, inertia[k].inertiaBody, inertia[k].inverseInertiaBody, w[k].torque, dt);
        });
        break;
    case Integrator::VelocityVerlet:
        velocityVerletStages(b, states, inertia, dt, evaluate, forEach);
        break;
    case Integrator::RK4:
        rk4Stages(b, states, inertia, dt, evaluate, forEach);
        break;
    }
    forEach(n, [&](std::size_t k) { states[k].rotation.orientation = glm::normalize(states[k].rotation.orientation); });
}

/// One step of the rotational equations alone (a body with no translation to speak of), the
/// torque (world frame) `torque(q, L)` evaluated at the method's stages: stepRigidSystem for one
/// body that feels no force.
template <class Torque>
inline void integrateRotation(Integrator integrator, Rotation& s, const dmat3& inverseInertiaBody, double dt,
                              Torque&& torque)
{
    RigidState state{dvec3(0.0), dvec3(0.0), s};
    const RigidInertia inertia{1.0, glm::inverse(inverseInertiaBody), inverseInertiaBody};
    stepRigidSystem(integrator, std::span<RigidState>(&state, 1), std::span<const RigidInertia>(&inertia, 1), dt,
                    [&](std::span<const RigidState> at, std::span<Wrench> out) {
                        out[0] = Wrench{dvec3(0.0), torque(at[0].rotation.orientation, at[0].rotation.momentum)};
                    });
    s = state.rotation;
}

} // namespace pba
