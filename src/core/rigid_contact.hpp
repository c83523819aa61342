#pragma once
// A rigid body against the room's planes (private to the core: the World calls it after each
// rigid body's step). Rigid against rigid is a later step.
#include <span>

#include "pba/collision.hpp"
#include "pba/rigid_body.hpp"
#include "pba/rotation.hpp"
#include "pba/shape.hpp"

namespace pba {

/// What the contact rule needs to know of a body besides its state.
struct ContactBody {
    const Shape& shape;
    std::span<const dvec3> points; ///< contactPointsOf(shape)
    RigidInertia inertia;
    double restitution;
    double friction;
    dvec3 gravity; ///< the world's gravitational acceleration
    double boundingRadius; ///< how far the shape reaches from its centre
    /// In: the last step's impulses (warm start); out: this step's.
    RigidBody::ContactMemory* memory = nullptr;
};

/// The step the contacts end.
struct ContactStep {
    const RigidState& start; ///< the body at the start of the step
    double dt;
    /// The part of the step's drift that its end velocity drives (driftWeight).
    double driftWeight;
    /// Below this speed a point arriving at a surface does not bounce.
    double restingSpeed;
};

/// How much of a method's position update its end velocity drives, for constant forces:
/// (semi-)implicit Euler's all of it (x1 = x0 + v1 dt), velocity Verlet's and RK4's half
/// (x1 = x0 + (v0 + v1) dt / 2), forward Euler's none (x1 = x0 + v0 dt).
double driftWeight(Integrator integrator);

/// 1/2 m v.v + 1/2 omega.L - m g.x.
double energyInGravity(const RigidState& s, const RigidInertia& inertia, const dvec3& gravity);

/// Resolves the contacts of a body that ended its free step at `s`, from `step.start`. Each
/// point that at the end's velocity would reach a plane (or the wall of a floor hole's shaft)
/// within the step is a contact, at the start's pose; the contacts are solved together as one
/// velocity problem by sequential impulses with accumulated, clamped impulses (Catto's method,
/// as in Box2D): every normal impulse non-negative; a point arriving faster than restingSpeed
/// leaves at e times its speed, a slower one may close its gap but not cross it (speculative
/// contact: resting stays at rest without jitter, and does not sink); friction opposes sliding
/// within mu times the normal impulse; and the sweeps run until the impulses stop changing, so
/// the result does not depend on the contacts' order (a box landing flat on four corners
/// rebounds flat). The impulses act at the start of the step: the end pose moves by the part of
/// the drift the end velocity drives. What a turning body's arcs still leave beyond a surface
/// is pushed out, and no contact leaves the body with more energy (energyInGravity) than the
/// larger of the step's start and its untouched end (the work of the other forces is kept): any
/// excess is taken from its motion. Returns whether a point bounced.
bool resolvePlaneContacts(const ContactBody& body, std::span<const Plane> planes, const ContactStep& step,
                          RigidState& s);

} // namespace pba
