#pragma once
// Forces are small generator objects held by the World (Cyclone's force registry,
// evaluated the way Jolt's step listener would be). The World asks each force, at every
// trial state an integrator needs, to add its force to the accumulators of the bodies it
// touches: one call covers every body, so a spring between two bodies pushes both ends at
// the same state (Newton's third law holds exactly).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "pba/clone_ptr.hpp"
#include "pba/math.hpp"
#include "pba/state.hpp"

namespace pba {

class Body;
class Force;
class Gravity;
class Drag;
class Spring;
class TwoBodySpring;
class SpringNetwork;
class BlowDryer;
struct SwarmFields;

/// How the app, the renderer and the studies learn what a force is without a type switch
/// (dynamic_cast): a visitor, with one visit per built-in force and one for any other (a user's
/// own), each doing nothing unless a caller overrides it, so a caller names only the forces it
/// draws or edits. Chosen over per-purpose virtuals on Force (a describeDrawing, the dryer's
/// settings, ...) because those purposes are the callers': the renderer's cone and coil, the
/// viewer's dryer sliders and the studies' exact solutions stay in their own layers, and a new
/// caller needs no change to the core. ForceEditor is the same for a caller that changes a force
/// (the viewer's dryer settings).
template <bool kConst>
class BasicForceVisitor {
    template <class F>
    using Ref = std::conditional_t<kConst, const F&, F&>;

public:
    virtual ~BasicForceVisitor() = default;
    virtual void visit(Ref<Gravity>) {}
    virtual void visit(Ref<Drag>) {}
    virtual void visit(Ref<Spring>) {}
    virtual void visit(Ref<TwoBodySpring>) {}
    virtual void visit(Ref<SpringNetwork>) {}
    virtual void visit(Ref<BlowDryer>) {}
    /// Any other force: one of a program's own.
    virtual void visit(Ref<Force>) {}
};
using ForceVisitor = BasicForceVisitor<true>;
using ForceEditor = BasicForceVisitor<false>;

/// How a body is turned at a trial state: a rigid body's orientation (body to world) and
/// angular velocity (world frame); a particle's is the identity and zero.
struct Pose {
    dquat orientation{1.0, 0.0, 0.0, 0.0};
    dvec3 angularVelocity{0.0};
};

/// The world's bodies at the trial states of one force evaluation.
struct BodyStates {
    std::span<const ClonePtr<Body>> bodies; ///< every body of the world (mass, name, fixed)
    std::span<const State> states;          ///< one per body: the trial state to evaluate at
    /// wanted[i] != 0: body i's force is needed (the World wants moving bodies only). Empty:
    /// every moving body's. A force may skip the bodies not wanted and the fixed ones (their
    /// accumulators are not read) but never needs to.
    std::span<const std::uint8_t> wanted;
    /// One per body, or empty: then each body's own. The World passes the masses it read at the
    /// start of the step, so a force on every body need not visit every body's object for it.
    std::span<const double> masses;
    /// One per body, or empty when no body of the world turns: a force applied at a point of a
    /// body (body-local offsets, surface samples) finds it at orientation(i).
    std::span<const Pose> poses;
    /// One per body, or empty: then each body's own (a particle's radius; 0 for any other body).
    std::span<const double> radii = {};

    /// Whether body i is wanted (every body is when there is no list), fixed or not.
    bool wants(std::size_t i) const { return wanted.empty() || wanted[i] != 0; }
    /// Whether body i's force is needed: wanted, or with no wanted list, not fixed.
    bool moving(std::size_t i) const { return wanted.empty() ? !isFixed(i) : wanted[i] != 0; }
    bool isFixed(std::size_t i) const;
    double mass(std::size_t i) const;
    double radius(std::size_t i) const;
    const Pose& pose(std::size_t i) const
    {
        static const Pose unturned;
        return poses.empty() ? unturned : poses[i];
    }
};

/// What forces add to, one entry per body of the world: the force through the body's centre,
/// and the torque about it (a wrench). A particle has no use for torque, so `torques` may be
/// empty; a force applied at a point off the centre (a rigid body's) adds the torque of its
/// lever arm only where there is somewhere to put it.
struct Accumulators {
    std::span<dvec3> forces;
    std::span<dvec3> torques; ///< empty when no body of the world can turn
    /// Working memory a force may use within one accumulate call (a spring network's force per
    /// spring), or null. It is the caller's, not the force's, so that two threads may evaluate
    /// one const force at once, each with its own; a caller that evaluates forces every step
    /// keeps one so that a step allocates nothing, and without one a force allocates its own.
    std::vector<dvec3>* scratch = nullptr;

    void add(std::size_t i, const dvec3& force) { forces[i] += force; }
    /// A force and a torque about body i's centre of mass (the sum of forces at several points).
    void add(std::size_t i, const dvec3& force, const dvec3& torque)
    {
        forces[i] += force;
        if (!torques.empty())
            torques[i] += torque;
    }
    /// A force applied at `arm` from body i's centre of mass: the same force, and arm x force.
    void addAt(std::size_t i, const dvec3& force, const dvec3& arm)
    {
        forces[i] += force;
        if (!torques.empty())
            torques[i] += glm::cross(arm, force);
    }
};

class Force {
public:
    virtual ~Force() = default;
    /// The scene-file type name: "gravity", "spring", "drag", ...
    virtual std::string_view type() const = 0;
    /// The force on body number `index` of the world, evaluated at the trial state (x, v), the
    /// other bodies being where they are. A force between bodies, which needs their trial states
    /// too, returns zero here and acts through accumulate.
    virtual dvec3 force(std::size_t index, const Body& body, const dvec3& x, const dvec3& v) const = 0;
    /// Adds this force to the accumulators of every moving body it acts on, for all of them in
    /// one call, at the trial states `in.states`. The default calls force(i, ...) for each wanted
    /// moving body in turn, so a force on one body at a time only writes force().
    virtual void accumulate(const BodyStates& in, Accumulators& out) const;
    /// Potential energy of the body at x for conservative forces; 0 for the others.
    virtual double potentialEnergy(std::size_t /*index*/, const Body& /*body*/, const dvec3& /*x*/) const { return 0.0; }
    /// Body `index`'s share of this force's potential energy at the states `in.states`. The
    /// default is potentialEnergy(index, ...); a force between bodies splits its energy among
    /// them, so that the shares add up to totalPotentialEnergy.
    virtual double potentialEnergyShare(std::size_t index, const BodyStates& in) const;
    /// This force's potential energy over every body, each interaction counted once.
    virtual double totalPotentialEnergy(const BodyStates& in) const;
    /// Appends the pairs of bodies this force couples (whose forces depend on each other's
    /// states): the World integrates such bodies together, as one system. None by default.
    virtual void appendCouplings(std::vector<std::pair<std::size_t, std::size_t>>& /*pairs*/) const {}
    virtual std::unique_ptr<Force> clone() const = 0;

    /// Adds what the force does to a swarm particle to `fields` (the float form a swarm's
    /// vectorised loop evaluates: gravity, drag, blow dryers) and returns true; returns false,
    /// as by default, when it cannot act on a swarm. A World with swarms refuses such a force
    /// (std::invalid_argument naming its type) rather than let it act on the bodies alone.
    virtual bool addToSwarmFields(SwarmFields& /*fields*/) const { return false; }
    /// Whether the force can add energy to the bodies: do positive work that no potential energy
    /// of its own accounts for (the blow dryer's push). A conservative force (gravity, a spring)
    /// or a dissipative one (drag, a damper) cannot, and says so; without an answer a force is
    /// taken to be a source, so that BlowUpWatch never calls a program's own force's work a
    /// blow-up.
    virtual bool addsEnergy() const { return true; }
    /// Calls the visit for the force's own type: ForceBase does it for every force derived
    /// from it; the default visits it as another force.
    virtual void accept(ForceVisitor& visitor) const { visitor.visit(*this); }
    virtual void accept(ForceEditor& editor) { editor.visit(*this); }
};

/// Helper so each force writes only its physics, not its copying or its visiting.
template <class Derived>
class ForceBase : public Force {
public:
    std::unique_ptr<Force> clone() const override { return std::make_unique<Derived>(static_cast<const Derived&>(*this)); }
    /// A built-in force meets its own visit; a program's own force the visit for any other.
    void accept(ForceVisitor& visitor) const override { visitor.visit(static_cast<const Derived&>(*this)); }
    void accept(ForceEditor& editor) override { editor.visit(static_cast<Derived&>(*this)); }
};

} // namespace pba
