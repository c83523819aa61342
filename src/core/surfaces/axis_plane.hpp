#pragma once
// A plane known, when the code is compiled, to face along a coordinate axis: the form a swarm's
// collision passes use for the walls of a room. Private to the core (see pba/collision.hpp).
#include <cmath>

#include "pba/collision.hpp"

namespace pba {

/// A plane whose normal is plus or minus coordinate axis kAxis (a wall, the floor or the
/// ceiling of a room), with the axis known when the code is compiled: the same geometry as
/// PlaneT, without the arithmetic of the normal's two zero components. The collision rule below
/// is written once, over the primitives both provide; a swarm's passes hand it this form for
/// the walls of its room, where the generic form did three times the arithmetic a particle
/// (the floor with the blow dryer's hole was a third of a settled swarm's step). For finite
/// coordinates it does what PlaneT does, rounding for rounding (tested; only the sign of a zero
/// may differ), but for where a compiler fuses a product into a sum, which is its choice for
/// each form.
template <class T, int kAxis>
struct AxisPlaneT {
    static_assert(kAxis >= 0 && kAxis < 3);
    /// The in-plane axes, in the order PlaneT's vectors hold them (so sums round alike).
    static constexpr int kU = kAxis == 0 ? 1 : 0, kV = kAxis == 2 ? 1 : 2;
    using InPlane = glm::vec<2, T, glm::defaultp>; ///< coordinates kU and kV

    T sign; ///< the normal's component on kAxis: 1 or -1
    T offset;
    T holeRadius;
    InPlane holeCentre; ///< the hole's centre, coordinates kU and kV

    /// `plane` must have plane.axis() == kAxis.
    explicit AxisPlaneT(const PlaneT<T>& plane)
        : sign(plane.normal[kAxis]), offset(plane.offset), holeRadius(plane.holeRadius),
          holeCentre(plane.holeCentre[kU], plane.holeCentre[kV])
    {
    }
    T distance(const Vec3<T>& x) const { return sign * x[kAxis] - offset; }
    T along(const Vec3<T>& v) const { return sign * v[kAxis]; }
    void moveAlong(Vec3<T>& x, T s) const { x[kAxis] += s * sign; }
    InPlane fromHoleAxis(const Vec3<T>& x) const { return InPlane(x[kU], x[kV]) - holeCentre; }
    T alongInPlane(const Vec3<T>& v, const InPlane& direction) const
    {
        return glm::dot(InPlane(v[kU], v[kV]), direction);
    }
    void moveInPlane(Vec3<T>& x, const InPlane& d) const
    {
        x[kU] += d.x;
        x[kV] += d.y;
    }
};

/// Calls f(plane) with the plane as an AxisPlaneT when its normal is a coordinate axis, as
/// itself otherwise: f is compiled for each form, and the call picks one per plane.
template <class T, class F>
inline decltype(auto) withPlaneGeometry(const PlaneT<T>& plane, F&& f)
{
    switch (plane.axis()) {
    case 0: return f(AxisPlaneT<T, 0>(plane));
    case 1: return f(AxisPlaneT<T, 1>(plane));
    case 2: return f(AxisPlaneT<T, 2>(plane));
    default: return f(plane);
    }
}

} // namespace pba
