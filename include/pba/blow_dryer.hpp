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
// The kernel is a template over the scalar with no data-dependent branches beyond
// selects, so a swarm loop over float arrays vectorises it.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

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

    template <class U>
    BlowDryerFieldT<U> as() const
    {
        return {Vec3<U>(nozzle), Vec3<U>(axis), U(height), U(nozzleRadius), U(topRadius), U(strength),
                axialFalloff, radialFalloff, direction};
    }
};
using BlowDryerField = BlowDryerFieldT<double>;

/// The field with its choices turned into numbers (each falloff a cubic's coefficients, the
/// direction a weight), so the force is arithmetic only: a swarm loop holds one of these and
/// vectorises; enums in the loop would stop it.
template <class T>
struct BlowDryerKernelT {
    Vec3<T> nozzle, axis;
    T height, nozzleRadius, inverseHeight, spread; ///< H, r0, 1 / H and R - r0
    T flowSpread;         ///< R - r0 for cone-flow, 0 for vertical: the weight of rho in the direction
    FalloffCubic<T> axial; ///< the strength times the axial profile: the force on the axis
    FalloffCubic<T> radial;

    BlowDryerKernelT() : BlowDryerKernelT(BlowDryerFieldT<T>{}) {}
    /// `scale` multiplies the force: a swarm passes 1 / m and gets the dryer's acceleration,
    /// one multiplication a particle fewer.
    explicit BlowDryerKernelT(const BlowDryerFieldT<T>& f, T scale = T(1))
        : nozzle(f.nozzle), axis(f.axis), height(f.height), nozzleRadius(f.nozzleRadius),
          inverseHeight(T(1) / f.height), spread(f.topRadius - f.nozzleRadius),
          flowSpread(f.direction == FlowDirection::ConeFlow ? spread : T(0)), axial(f.axialFalloff, scale * f.strength),
          radial(f.radialFalloff)
    {
    }
};

/// What the kernel knows of the dryer's axis when it is compiled: nothing (`Any`), or that it is
/// exactly +y (`Up`, every built-in scene), which turns the axial and radial projections into
/// picking coordinates: a sixth fewer multiplications in a swarm step, measured about 15%
/// faster on all cores. Both are the same arithmetic otherwise.
enum class DryerAxis { Any, Up };

/// The force of the field at x (independent of the body's mass and velocity).
///
/// Written for the swarm loop, where square roots and divisions are the slow instructions:
/// two of each a particle, none waiting for another. With q = R(h) (the radius here) and
/// c = w (R - r0) / q (w = 1 for cone-flow, 0 for vertical), the flow direction is H axis + c rho,
/// and since rho is perpendicular to the axis its length is sqrt(H^2 + c^2 r^2) =
/// sqrt(H^2 q^2 + w^2 (R - r0)^2 r^2) / q: that root is taken from r^2, beside r's own, and
/// 1/q (for r/q and c) and q / root (1 / the length) are two divisions. One division,
/// 1 / (q root), gave both, but chained root, product, division and products one after another:
/// a swarm loop over a block in L1 measured 18% slower that way (0.83 against 0.68 ns a
/// particle), the out-of-order core having less to do while it waited.
template <DryerAxis kAxis = DryerAxis::Any, class T>
inline Vec3<T> blowDryerForce(const BlowDryerKernelT<T>& f, const Vec3<T>& x)
{
    constexpr bool kUp = kAxis == DryerAxis::Up;
    const Vec3<T> d = x - f.nozzle;
    const T h = kUp ? d.y : glm::dot(d, f.axis);
    const Vec3<T> rho = kUp ? Vec3<T>(d.x, T(0), d.z) : d - h * f.axis;
    const T r2 = kUp ? d.x * d.x + d.z * d.z : glm::dot(rho, rho);
    const T r = std::sqrt(r2);
    const T s = h * f.inverseHeight;
    const T radiusHere = f.nozzleRadius + f.spread * s;
    // Selects rather than branches: the same arithmetic for every particle (a vectorised loop
    // turns them into masked moves, cheaper than multiplying by masks as numbers).
    const bool inside = (h >= T(0)) & (s < T(1)) & (r < radiusHere);
    // Computed for every particle, as if inside: outside, q may be zero or negative and what
    // follows infinite or NaN, but only the two selects below read it (no traps are enabled).
    // Selecting q itself instead made GCC compute the roots and the division twice, once per
    // value of q.
    const T q = radiusHere;
    const T root = std::sqrt(f.height * f.height * q * q + f.flowSpread * f.flowSpread * r2); // q |flow|
    const T inverseRadius = T(1) / q;
    const T inverseLength = q / root; // 1 / |flow|
    // Inside the cone both falloffs' arguments lie in (0, 1]: no clamps.
    const T magnitude = f.axial.inRange(T(1) - s) * f.radial.inRange(T(1) - r * inverseRadius);
    // Vertical: the axis. Cone-flow: H axis + (R - r0) rho / R(h).
    const T scale = inside ? magnitude * inverseLength : T(0);
    const T radial = inside ? scale * f.flowSpread * inverseRadius : T(0);
    if constexpr (kUp)
        return Vec3<T>(radial * d.x, scale * f.height, radial * d.z);
    else
        return scale * f.height * f.axis + radial * rho;
}

template <class T>
inline Vec3<T> blowDryerForce(const BlowDryerFieldT<T>& f, const Vec3<T>& x)
{
    return blowDryerForce(BlowDryerKernelT<T>(f), x);
}

/// The field as a Force of the World.
class BlowDryer final : public ForceBase<BlowDryer> {
public:
    explicit BlowDryer(const BlowDryerField& field) : m_field(field) {}
    std::string_view type() const override { return "blow-dryer"; }
    dvec3 force(std::size_t, const Body&, const dvec3& x, const dvec3&) const override
    {
        return blowDryerForce(m_field, x);
    }
    const BlowDryerField& field() const { return m_field; }
    BlowDryerField& field() { return m_field; }

private:
    BlowDryerField m_field;
};

} // namespace pba
