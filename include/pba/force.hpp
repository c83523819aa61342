#pragma once
// Forces are small generator objects held by the World (Cyclone's force registry,
// evaluated the way Jolt's step listener would be): the World sums them into an
// acceleration at whatever trial state an integrator asks about.
#include <cstddef>
#include <memory>
#include <string_view>
#include <type_traits>

#include "pba/math.hpp"

namespace pba {

class Body;
class Force;
class Gravity;
class Drag;
class Spring;
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
    virtual void visit(Ref<BlowDryer>) {}
    /// Any other force: one of a program's own.
    virtual void visit(Ref<Force>) {}
};
using ForceVisitor = BasicForceVisitor<true>;
using ForceEditor = BasicForceVisitor<false>;

class Force {
public:
    virtual ~Force() = default;
    /// The scene-file type name: "gravity", "spring", "drag", ...
    virtual std::string_view type() const = 0;
    /// The force on body number `index` of the world, evaluated at the trial state (x, v).
    virtual dvec3 force(std::size_t index, const Body& body, const dvec3& x, const dvec3& v) const = 0;
    /// Potential energy of the body at x for conservative forces; 0 for the others.
    virtual double potentialEnergy(std::size_t /*index*/, const Body& /*body*/, const dvec3& /*x*/) const { return 0.0; }
    virtual std::unique_ptr<Force> clone() const = 0;

    /// Adds what the force does to a swarm particle to `fields` (the float form a swarm's
    /// vectorised loop evaluates: gravity, drag, blow dryers) and returns true; returns false,
    /// as by default, when it cannot act on a swarm. A World with swarms refuses such a force
    /// (std::invalid_argument naming its type) rather than let it act on the bodies alone.
    virtual bool addToSwarmFields(SwarmFields& /*fields*/) const { return false; }
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
