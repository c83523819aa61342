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
#include <utility>
#include <vector>

#include "pba/clone_ptr.hpp"
#include "pba/math.hpp"
#include "pba/state.hpp"

namespace pba {

class Body;

/// The world's bodies at the trial states of one force evaluation.
struct BodyStates {
    std::span<const ClonePtr<Body>> bodies; ///< every body of the world (mass, name, fixed)
    std::span<const State> states;          ///< one per body: the trial state to evaluate at
    /// wanted[i] != 0: body i's force is needed. Empty: every moving body's. A force may skip
    /// the bodies not wanted (their accumulators are not read) but never needs to.
    std::span<const std::uint8_t> wanted;

    bool wants(std::size_t i) const { return wanted.empty() || wanted[i] != 0; }
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
    /// Adds this force to forces[i] for every moving body i it acts on, at the trial states
    /// `in.states`. The default calls force(i, ...) for each wanted moving body, so a force on
    /// one body at a time only writes force().
    virtual void accumulate(const BodyStates& in, std::span<dvec3> forces) const;
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
};

/// Helper so each force writes only its physics, not its copying.
template <class Derived>
class ForceBase : public Force {
public:
    std::unique_ptr<Force> clone() const override { return std::make_unique<Derived>(static_cast<const Derived&>(*this)); }
};

} // namespace pba
