#pragma once
// The damped spring's force, the kernel of Spring, TwoBodySpring and the spring networks of
// ropes and cloth: private to the core, which alone evaluates it.
#include "pba/math.hpp"

namespace pba {

/// Damped spring between an anchor and a point: F = -k (|d| - L) d/|d| - c (v . d/|d|) d/|d|,
/// with d = x - anchor and v the point's velocity relative to the anchor's.
template <class T>
inline Vec3<T> springForce(const Vec3<T>& anchor, T stiffness, T restLength, T damping, const Vec3<T>& x, const Vec3<T>& v)
{
    const Vec3<T> d = x - anchor;
    const T length = glm::length(d);
    if (length <= T(0))
        return Vec3<T>(T(0)); // direction undefined at the anchor: no force rather than NaN
    const Vec3<T> u = d * (T(1) / length); // one division rather than three
    return -(stiffness * (length - restLength) + damping * glm::dot(v, u)) * u;
}

} // namespace pba
