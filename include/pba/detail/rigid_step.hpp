#pragma once
// The definitions of rotation.hpp's templates: each method's stages for a system of rigid bodies.
// Included by rotation.hpp (which declares them and documents each method); not meant to be
// included on its own.
#include <stdexcept>
#include <string>

#include "pba/rotation.hpp"

namespace pba {

namespace rigid_detail {

/// dq/dt at a stage whose q is not exactly unit (RK4's and Verlet's intermediate stages): omega
/// from the normalised orientation, applied to q itself.
inline dquat rate(const dquat& q, const dmat3& inverseInertiaBody, const dvec3& momentum)
{
    return orientationRate(q, angularVelocity(glm::normalize(q), inverseInertiaBody, momentum));
}

inline Derivative derivative(const RigidState& s, const Wrench& w, const RigidInertia& m)
{
    return {s.v, w.force * m.inverseMass, rate(s.rotation.orientation, m.inverseInertiaBody, s.rotation.momentum),
            w.torque};
}

/// s + h * (the derivative d).
inline RigidState advance(const RigidState& s, const Derivative& d, double h)
{
    return {s.x + d.dx * h, s.v + d.dv * h, Rotation{s.rotation.orientation + d.dq * h, s.rotation.momentum + d.dl * h}};
}

/// stepRigidSystem's velocity Verlet and splitting, from the start's wrenches in b.w (see there):
/// the same kicks and the same drift of x, so the splitting's translation is velocity Verlet's to
/// the bit; q drifts by the midpoint rule (Verlet) or by the free body's flow (`splitting`).
template <class Evaluate, class ForEach>
void velocityVerletStages(RigidStepBuffers& b, std::span<RigidState> states, std::span<const RigidInertia> inertia,
                          double dt, bool splitting, Evaluate&& evaluate, ForEach&& forEach)
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
        dquat q1;
        if (splitting) {
            q1 = freeRotation(q0, half, inertia[k].inertiaBody, dt);
        } else {
            const dquat mid = glm::normalize(q0 + rate(q0, inertia[k].inverseInertiaBody, half) * (0.5 * dt));
            q1 = q0 + rate(mid, inertia[k].inverseInertiaBody, half) * dt;
        }
        stage[k] = {s0.x + s0.v * dt + a0 * (0.5 * dt * dt), s0.v + a0 * dt,
                    Rotation{q1, s0.rotation.momentum + w0[k].torque * dt}};
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

template <class Wrenches, class ForEach>
void stepRigidSystem(Integrator integrator, std::span<RigidState> states, std::span<const RigidInertia> inertia,
                     double dt, Wrenches&& wrenches, ForEach&& forEach, RigidStepBuffers* buffers)
{
    using namespace rigid_detail;
    if (isSpringSystemMethod(integrator))
        throw std::invalid_argument(std::string(integratorName(integrator)) +
                                    " steps particles joined by springs, not rigid bodies");
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
    case Integrator::Splitting:
        velocityVerletStages(b, states, inertia, dt, integrator == Integrator::Splitting, evaluate, forEach);
        break;
    case Integrator::RK4:
        rk4Stages(b, states, inertia, dt, evaluate, forEach);
        break;
    case Integrator::ImplicitEuler:
    case Integrator::Xpbd:
        break; // refused above
    }
    forEach(n, [&](std::size_t k) { states[k].rotation.orientation = glm::normalize(states[k].rotation.orientation); });
}

template <class Torque>
void integrateRotation(Integrator integrator, Rotation& s, const dmat3& inverseInertiaBody, double dt, Torque&& torque)
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
