#pragma once
// A rigid body as the contact and joint solvers see it during one step: its velocities at the end
// of its free step (its own integrator's, under every force), which the impulses change, and the
// corrections those impulses make to its end pose. Static bodies (fixed ones, the room's
// surfaces) have zero inverse mass and inertia and never move.
#include <cstdint>

#include <glm/gtc/quaternion.hpp>

#include "pba/integrator.hpp"
#include "pba/math.hpp"

namespace pba::rigid {

/// How much of a method's position update its end velocity drives, for constant forces:
/// (semi-)implicit Euler's all of it (x1 = x0 + v1 dt), velocity Verlet's, the splitting's (whose
/// translation is velocity Verlet) and RK4's half (x1 = x0 + (v0 + v1) dt / 2), forward Euler's
/// none (x1 = x0 + v0 dt). An impulse that changes
/// the end velocity moves the end position by that share of it times dt, so that a body resting
/// on a surface stays exactly where it is whatever its integrator.
inline double driftWeight(Integrator integrator)
{
    switch (integrator) {
    case Integrator::ForwardEuler: return 0.0;
    case Integrator::VelocityVerlet:
    case Integrator::Splitting:
    case Integrator::RK4: return 0.5;
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitGyroscopic:
    case Integrator::ImplicitEuler: // not a rigid body's: World::step refuses them
    case Integrator::Xpbd: return 1.0;
    }
    return 1.0;
}

struct SolverBody {
    dvec3 position{0.0};   ///< the centre of mass at the start of the step (the arms' origin)
    dquat orientation{1.0, 0.0, 0.0, 0.0}; ///< at the start of the step
    dvec3 v{0.0};          ///< linear velocity at the end of the step, world
    dvec3 w{0.0};          ///< angular velocity at the end of the step, world
    dvec3 vStart{0.0};     ///< linear velocity at the start of the step
    dvec3 wStart{0.0};     ///< angular velocity at the start of the step
    dvec3 vFree{0.0};      ///< linear velocity at the end of the free step, before any impulse
    dvec3 wFree{0.0};      ///< angular velocity likewise
    dvec3 shift{0.0};      ///< how far the impulses moved the end position
    dvec3 turn{0.0};       ///< how far they turned the end orientation (a rotation vector)
    dmat3 inverseInertia{0.0}; ///< world frame, at the start's orientation
    dmat3 inertia{0.0};        ///< its inverse: what turns a change of w back into one of L
    double inverseMass = 0.0;
    /// The part of the step's drift that a change of the end velocity drives (driftWeight):
    /// semi-implicit Euler's all of it, velocity Verlet's and RK4's half, forward Euler's none.
    double driftWeight = 1.0;
    /// The latest time within the step at which it took a restitution impulse (collision pass).
    double lastImpact = 0.0;
    /// Whether it took a restitution impulse this step.
    bool struck = false;

    /// The body's end pose: its free step's until the passes move it (the collision pass reads
    /// the free one, to find where the body was when a point arrived).
    dvec3 endPosition{0.0};
    dquat endOrientation{1.0, 0.0, 0.0, 0.0};

    bool isStatic() const { return inverseMass == 0.0; }
    /// Where its free path had it at `fraction` of the step (0 the start), its acceleration
    /// taken as constant: the path the collision pass finds times of arrival on.
    dvec3 freePosition(double fraction, double dt) const
    {
        return position + (vStart * fraction + 0.5 * (vFree - vStart) * (fraction * fraction)) * dt;
    }
    dquat freeOrientation(double fraction) const
    {
        return isStatic() ? orientation : glm::slerp(orientation, endOrientation, fraction);
    }
    /// An impulse p at arm r (from the centre of mass), added to the end velocities.
    void applyImpulse(const dvec3& p, const dvec3& r)
    {
        if (isStatic()) // shared by the islands that touch it: never written
            return;
        v += p * inverseMass;
        w += inverseInertia * glm::cross(r, p);
    }
    /// An angular impulse l (world frame).
    void applyAngularImpulse(const dvec3& l)
    {
        if (isStatic())
            return;
        w += inverseInertia * l;
    }
    /// The position pass's moves: a positional impulse p at arm r, or an angular one l, on the
    /// end pose alone.
    void movePose(const dvec3& p, const dvec3& r);
    void turnPose(const dvec3& l);
    /// The angular momentum the impulses have added: every change of w came from one.
    dvec3 momentumChange() const { return inertia * (w - wFree); }
    /// The velocity of the point at arm r.
    dvec3 pointVelocity(const dvec3& r) const { return v + glm::cross(w, r); }
    dvec3 pointStartVelocity(const dvec3& r) const { return vStart + glm::cross(wStart, r); }
    /// The velocities it has at `fraction` of the step on its present path: the impulses so far
    /// with the free step's (constant) acceleration up to then.
    dvec3 velocityAt(double fraction) const { return v - (vFree - vStart) * (1.0 - fraction); }
    dvec3 spinAt(double fraction) const { return w - (wFree - wStart) * (1.0 - fraction); }
};

/// A body that a blow moves as its one joint lets it: joined by nothing else, to the world or a
/// static body, it turns about the joint's anchor (a ball joint), about the hinge's axis (a
/// hinge with no limit near), or not at all (a fixed joint). The collision pass gives its blows
/// that mass, so that a plank hinged on a stand meets the stand in the blow, which sequential
/// sweeps of the hinge's rows and the stand's point could not reach in a step (a lever of 12:1
/// left the plank turning and a box on its other end thrown 0.44 m up).
struct Pin {
    std::uint32_t body = 0;
    dvec3 arm{0.0};            ///< from the anchor to the centre of mass, world
    dmat3 inverseInertia{0.0}; ///< about the anchor, on the turns it may take

    /// The inverse of the mass its point at arm r (from the centre) has along u.
    double inverseMassAlong(const dvec3& r, const dvec3& u) const
    {
        const dvec3 c = glm::cross(arm + r, u);
        return glm::dot(c, inverseInertia * c);
    }
    /// An impulse p at arm r: a turn about the anchor, which carries the centre along.
    void applyImpulse(SolverBody& b, const dvec3& p, const dvec3& r) const
    {
        const dvec3 dw = inverseInertia * glm::cross(arm + r, p);
        b.w += dw;
        b.v += glm::cross(dw, arm);
    }
};

/// q turned by the small rotation vector theta (world frame), renormalised. Divided by its
/// length rather than glm::normalize'd: that makes a zero quaternion (an orientation whose
/// spin overflowed) the identity, and the blow-up would go unseen; here it stays not finite.
inline dquat turned(const dquat& q, const dvec3& theta)
{
    const dquat t = q + dquat(0.0, theta.x, theta.y, theta.z) * q * 0.5;
    return t / glm::length(t);
}

/// The end orientation q1 of a step that turned q0 as semi-implicit Euler and the implicit
/// gyroscopic step do, q1 = q0 + 1/2 (omega dt) q0 normalised, with theta added to that omega dt.
/// Applied after the step's turn instead (turned), theta misses what the two turns do together,
/// which for a body spinning radians a step is as large as theta: a bead spun up by the floor
/// about its hinge's axis was turned off the axis and thrown back onto it a metre a step.
inline dquat turnedWithin(const dquat& q0, const dquat& q1, const dvec3& theta)
{
    const dquat step = q1 * glm::conjugate(q0); // 1 + 1/2 omega dt, normalised: its real part is positive
    if (!(step.w > 0.0))
        return turned(q1, theta);
    const dquat t = (step / step.w + dquat(0.0, theta.x, theta.y, theta.z) * 0.5) * q0;
    return t / glm::length(t);
}

/// The end orientation q1 (the step's from q0) turned further by theta, the impulses' share of
/// the step's turn: within the step's turn for a method whose whole turn its end velocity drives
/// (driftWeight 1: turnedWithin), after it for the others.
inline dquat turnedByImpulses(const dquat& q0, const dquat& q1, const dvec3& theta, double driftWeight)
{
    return driftWeight == 1.0 && theta != dvec3(0.0) ? turnedWithin(q0, q1, theta) : turned(q1, theta);
}

inline void SolverBody::movePose(const dvec3& p, const dvec3& r)
{
    if (isStatic())
        return;
    endPosition += p * inverseMass;
    endOrientation = turned(endOrientation, inverseInertia * glm::cross(r, p));
}

inline void SolverBody::turnPose(const dvec3& l)
{
    if (isStatic())
        return;
    endOrientation = turned(endOrientation, inverseInertia * l);
}

/// [r]x, the matrix of r x (.).
inline dmat3 skew(const dvec3& r) { return dmat3(0.0, r.z, -r.y, -r.z, 0.0, r.x, r.y, -r.x, 0.0); }

/// What an impulse p at arm r does to the velocity of the body's point there: (1/m I - [r]x I^-1 [r]x) p.
inline dmat3 bodyPointMass(const SolverBody& body, const dvec3& r)
{
    const dmat3 s = skew(r);
    return dmat3(body.inverseMass) - s * body.inverseInertia * s;
}

/// What an impulse P at arms rA (on A, negated) and rB (on B) does to the two points' relative
/// velocity: K P, with K = (1/mA + 1/mB) I - [rA]x IA^-1 [rA]x - [rB]x IB^-1 [rB]x.
inline dmat3 pointMass(const SolverBody& a, const SolverBody& b, const dvec3& ra, const dvec3& rb)
{
    return bodyPointMass(a, ra) + bodyPointMass(b, rb);
}

} // namespace pba::rigid
