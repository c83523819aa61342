#pragma once
// Forces are small generator objects held by the World (Cyclone's force registry,
// evaluated the way Jolt's step listener would be): the World sums them into an
// acceleration at whatever trial state an integrator asks about.
#include <cstddef>
#include <memory>
#include <string_view>

#include "pba/math.hpp"

namespace pba {

class Body;

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
};

/// Helper so each force writes only its physics, not its copying.
template <class Derived>
class ForceBase : public Force {
public:
    std::unique_ptr<Force> clone() const override { return std::make_unique<Derived>(static_cast<const Derived&>(*this)); }
};

} // namespace pba
