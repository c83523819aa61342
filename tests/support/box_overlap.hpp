#pragma once
// How deep two oriented boxes overlap, found independently of the engine: the separating-axis
// test over the 15 axes of two boxes (each one's three face normals and the nine cross products
// of their edges), the overlap along each, the least of them. Zero or less: they do not overlap.
#include <algorithm>
#include <cmath>
#include <limits>

#include "pba/math.hpp"

namespace pba::test {

struct OrientedBox {
    dvec3 centre{0.0};
    dmat3 axes{1.0};    ///< columns: the box's own x, y and z in the world
    dvec3 half{0.5};    ///< half extents along them
};

inline double overlapDepth(const OrientedBox& a, const OrientedBox& b)
{
    const dvec3 d = b.centre - a.centre;
    double least = std::numeric_limits<double>::infinity();
    auto test = [&](const dvec3& axis) {
        const double len = glm::length(axis);
        if (len < 1e-9)
            return; // parallel edges: their cross product is no axis
        const dvec3 u = axis / len;
        double ra = 0.0, rb = 0.0;
        for (int k = 0; k < 3; ++k) {
            ra += a.half[k] * std::abs(glm::dot(a.axes[k], u));
            rb += b.half[k] * std::abs(glm::dot(b.axes[k], u));
        }
        least = std::min(least, ra + rb - std::abs(glm::dot(d, u)));
    };
    for (int k = 0; k < 3; ++k) {
        test(a.axes[k]);
        test(b.axes[k]);
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            test(glm::cross(a.axes[i], b.axes[j]));
    return least;
}

} // namespace pba::test
