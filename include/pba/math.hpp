#pragma once
// The vector types every part of pba shares. Simulation state is double
// precision (the integrator study measures errors far below float's rounding);
// kernels are templates over the scalar so swarms can run them in float.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace pba {

using glm::dmat3;
using glm::dquat;
using glm::dvec3;
template <class T>
using Vec3 = glm::vec<3, T, glm::defaultp>;

/// `v` scaled to length 1, or zero when it has no direction (zero, or not finite). Divided by
/// its largest component first: glm::normalize squares the components, so an axis given as
/// [1e160, 0, 0] would overflow and [1e-200, 0, 0] vanish.
inline dvec3 unitOrZero(const dvec3& v)
{
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!(largest > 0.0) || !std::isfinite(largest))
        return dvec3(0.0);
    const dvec3 scaled = v / largest;
    return scaled / glm::length(scaled);
}

/// The same for a quaternion given as an orientation.
inline dquat unitOrZero(const dquat& q)
{
    const double largest = std::max({std::abs(q.w), std::abs(q.x), std::abs(q.y), std::abs(q.z)});
    if (!(largest > 0.0) || !std::isfinite(largest))
        return dquat(0.0, 0.0, 0.0, 0.0);
    const dquat scaled = q / largest;
    return scaled / glm::length(scaled);
}

} // namespace pba
