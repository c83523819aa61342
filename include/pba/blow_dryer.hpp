#pragma once
// Task 4's blow dryer: a conical force field rising from a hole in the floor.
//
// The region of influence is the frustum between a disc of radius r0 at the nozzle and
// a disc of radius R at height H along the axis. Inside it the force is
//     F = strength * axial(1 - h/H) * radial(1 - r/R(h)) * direction,
// with R(h) = r0 + (R - r0) h/H, so it is strongest on the axis at the nozzle and zero at
// the top, on the edge and outside. `direction` is the axis ("vertical", the basic task)
// or, in "cone-flow" mode, normalize(H axis + (R - r0) rho / R(h)) where rho is the radial
// offset: the axis on the axis, parallel to the cone's side at the edge, blended linearly
// in between, always away from the nozzle, and never dividing by r (continuous on the axis).
//
// A dryer that blows up through a hole in the floor (`shaft`) pushes in the hole's shaft too:
// below the nozzle, within r0 of it, the force is the nozzle's, strength * axis, the same across
// the shaft (a short duct's flow is nearly uniform: plug flow). So whatever falls into the hole
// is blown out again when the dryer is stronger than its weight.
//
// Two opt-in terms make the field an airflow that can hold a ball (both off by default, when the
// force is exactly the one above). Let w(x) in [0, 1] be the profile (the force over the
// strength: axial(1 - h/H) radial(1 - r/R(h)) in the cone, 1 in the shaft, 0 elsewhere) and
// u(x) = U w(x) direction the air's velocity, U = `airSpeed` at the nozzle:
//  - air drag: the ball feels the air as drag on its velocity relative to the air's,
//    c (u - v) with c = strength / U, so a ball at rest feels exactly the force above and a
//    moving one is damped toward the air's velocity (time constant m / c). Only where the air
//    blows (the cone and the shaft): the room's still air is the `drag` force's business.
//  - axis pull (Bernoulli): the air is fastest on the axis, where its pressure is lowest, and a
//    ball of volume V feels -V grad p = (rho V / 2) grad |u|^2. With beta = `axisPull` (kg: the
//    air mass the ball displaces, times a shape factor), the part across the axis,
//    (beta / 2) grad_perp |u|^2 = beta U^2 w dw/dr rho/r, pulls toward the axis; the part along
//    it is left out, so the hover height stays the one the push alone gives.
//
// A third opt-in term, `airDensity` rho_a, makes the air act on a ball by its size: a body with a
// radius r (a particle, a swarm's grain) then feels, instead of the push and the air drag above,
// the quadratic drag of the air on its cross-section, F = (1/2) rho_a C_d pi r^2 |u - v| (u - v),
// and the pull with beta = rho_a (4/3) pi r^3, the air it displaces. Its weight decides where it
// hovers, not the strength: a 2.7 g, 40 mm ping-pong ball floats where |u| = sqrt(2 m g /
// (rho_a C_d pi r^2)), 8.6 m/s. A body without a radius still feels the strength's push.
//
// The force's kernel, which a swarm's loop inlines and vectorises, is pba/detail/blow_dryer_kernel.hpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "pba/force.hpp"
#include "pba/math.hpp"

namespace pba {

enum class Falloff { Linear, Quadratic, Smooth };
enum class FlowDirection { Vertical, ConeFlow };

std::string_view falloffName(Falloff falloff);
std::optional<Falloff> falloffFromName(std::string_view name);
std::string_view flowDirectionName(FlowDirection direction);
std::optional<FlowDirection> flowDirectionFromName(std::string_view name);

/// A falloff profile of u in [0, 1]: 0 at u = 0, 1 at u = 1. `linear` u, `quadratic` u^2,
/// `smooth` the smoothstep u^2 (3 - 2u), flat at both ends. Every profile is a cubic
/// u (a + u (b + c u)), so a profile is three numbers rather than a switch: a loop over many
/// particles has no branch and vectorises, and the cubic costs three multiply-adds.
template <class T>
struct FalloffCubic {
    T a, b, c;

    /// The profile times `scale` (which the force kernel sets to the dryer's strength).
    explicit FalloffCubic(Falloff kind, T scale = T(1))
        : a(scale * T(kind == Falloff::Linear)),
          b(scale * (T(kind == Falloff::Quadratic) + T(3) * T(kind == Falloff::Smooth))),
          c(scale * T(-2) * T(kind == Falloff::Smooth))
    {
    }
    T operator()(T u) const { return inRange(std::min(std::max(u, T(0)), T(1))); }
    /// For u known to lie in [0, 1] (inside the cone): no clamp, three multiply-adds.
    T inRange(T u) const { return u * (a + u * (b + c * u)); }
    /// The slope d/du: a + 2 b u + 3 c u^2, never negative on [0, 1].
    T slope(T u) const { return a + u * (T(2) * b + T(3) * c * u); }
};

template <class T>
inline T falloff(Falloff kind, T u)
{
    return FalloffCubic<T>(kind)(u);
}

template <class T>
struct BlowDryerFieldT {
    Vec3<T> nozzle{T(0)};           ///< centre of the hole in the floor, m
    Vec3<T> axis{T(0), T(1), T(0)}; ///< unit vector, the direction of the flow
    T height = T(1);                ///< H, m
    T nozzleRadius = T(0);          ///< r0, m
    T topRadius = T(1);             ///< R, m
    T strength = T(0);              ///< force at the nozzle on the axis, N
    Falloff axialFalloff = Falloff::Linear;
    Falloff radialFalloff = Falloff::Linear;
    FlowDirection direction = FlowDirection::Vertical;
    bool shaft = false;             ///< blows up through a hole of radius r0 in the floor: pushes in its shaft
    T airSpeed = T(0);              ///< U, the air's speed at the nozzle on the axis, m/s; 0: no air drag
    T axisPull = T(0);              ///< beta, kg: the Bernoulli pull toward the axis (needs airSpeed)
    T airDensity = T(0);            ///< rho_a, kg/m^3: a ball feels the air on its cross-section (needs airSpeed); 0: off
    T dragCoefficient = T(0.47);    ///< C_d of a ball in that air (a smooth sphere's)

    /// The air drag's coefficient c = strength / U (0 without air speed), N s/m.
    T airDrag() const { return airSpeed > T(0) ? strength / airSpeed : T(0); }

    template <class U>
    BlowDryerFieldT<U> as() const
    {
        return {Vec3<U>(nozzle), Vec3<U>(axis), U(height), U(nozzleRadius), U(topRadius), U(strength),
                axialFalloff, radialFalloff, direction, shaft, U(airSpeed), U(axisPull), U(airDensity),
                U(dragCoefficient)};
    }
};
using BlowDryerField = BlowDryerFieldT<double>;

/// The field's force at x on a body of radius `radius` moving at v (see the header's comment),
/// its air terms included.
dvec3 blowDryerForce(const BlowDryerField& f, const dvec3& x, const dvec3& v = dvec3(0.0), double radius = 0.0);

/// The air's velocity u = U w direction at x (zero without air speed): what the air drag pulls
/// a body's velocity toward, and whose squared length the axis pull climbs.
dvec3 blowDryerAirVelocity(const BlowDryerField& f, const dvec3& x);

/// Whether x is inside the dryer's cone (its region of influence above the nozzle).
bool insideBlowDryerCone(const BlowDryerField& f, const dvec3& x);

/// Whether x is under the hole of a dryer that sits in the floor (in its shaft, or lower).
bool insideBlowDryerShaft(const BlowDryerField& f, const dvec3& x);

template <class T>
struct BlowDryerKernelT;

/// The field as a Force of the World.
class BlowDryer final : public ForceBase<BlowDryer> {
public:
    explicit BlowDryer(const BlowDryerField& field);
    std::string_view type() const override { return "blow-dryer"; }
    dvec3 force(std::size_t, const Body&, const dvec3& x, const dvec3& v) const override;
    /// On all cores, the kernel inlined in the loop (no call per body).
    void accumulate(const BodyStates& in, Accumulators& out) const override;
    bool addToSwarmFields(SwarmFields& fields) const override;
    /// The fan's push does work that no potential energy accounts for: an energy source.
    bool addsEnergy() const override { return true; }
    const BlowDryerField& field() const { return m_field; }
    void setField(const BlowDryerField& field);

private:
    BlowDryerField m_field;
    /// The field's numbers made once (a division and the falloffs' cubics), not per body and
    /// stage: on a 16,384-particle cloth, remaking it in every call was most of the dryer's cost.
    /// Shared by copies: it changes only with setField, which makes a new one.
    std::shared_ptr<const BlowDryerKernelT<double>> m_kernel;
};

class World;

/// A blow dryer among a world's forces: its index (World::force) and its field.
struct WorldDryer {
    std::size_t force;
    BlowDryerField field;
};

/// The world's blow dryers in the order of its forces (what the viewer's settings, the renderer's
/// cones, `pba field` and the jet's read-outs work on), found through the ForceVisitor.
std::vector<WorldDryer> blowDryers(const World& world);

} // namespace pba
