#pragma once
// Mass, centre of mass and inertia tensor of the shapes a rigid body can take (the practical's
// "density and inertia tensor ... in a few weeks"): closed forms for the box, the sphere and
// the cylinder, and for a closed triangle mesh the integrals over its volume turned into sums
// over its triangles by the divergence theorem (Eberly, "Polyhedral Mass Properties
// (Revisited)", after Mirtich 1996). A rigid body is built from these; they know no body.
#include <cstdint>
#include <span>

#include "pba/math.hpp"

namespace pba {

struct MassProperties {
    double mass = 0.0;    ///< kg
    dvec3 centre{0.0};    ///< centre of mass in the shape's own frame, m
    dmat3 inertia{0.0};   ///< inertia tensor about the centre of mass, in the shape's frame, kg m^2

    /// The same shape at another uniform density, such that its mass is `mass` (> 0): the
    /// inertia scales with it, the centre stays.
    MassProperties withMass(double mass) const;
};

/// A box of sides `size` (x, y, z), centred on the origin, of uniform `density` (kg/m^3).
/// Each argument must be finite and positive: std::invalid_argument otherwise.
MassProperties boxMassProperties(const dvec3& size, double density);
/// A ball of `radius` centred on the origin.
MassProperties sphereMassProperties(double radius, double density);
/// A solid cylinder of `radius` and `height` along the y axis, centred on the origin.
MassProperties cylinderMassProperties(double radius, double height, double density);
/// A closed triangle mesh: `triangles` holds three vertex indices a triangle, counter-clockwise
/// seen from outside (outward normals). std::invalid_argument, saying why, for an index out of
/// range, a mesh that is not closed (an edge not shared by exactly two triangles in opposite
/// directions) or whose volume is not positive (turned inside out).
MassProperties meshMassProperties(std::span<const dvec3> vertices, std::span<const std::uint32_t> triangles,
                                  double density);

} // namespace pba
