#pragma once
// What the narrow phase finds between two shapes: a contact manifold of up to four points that
// share one normal (Box2D's b2Manifold, Jolt's ContactManifold). Each point carries a feature id,
// which stays the same while the same two features (a vertex and a face, two edges) touch, so that
// the contact cache can hand a point the impulses it ended the last step with.
#include <array>
#include <cstdint>

#include "pba/math.hpp"

namespace pba::contact {

/// A body's frame: body coordinates to world, x_world = position + rotation * x_body.
struct Transform {
    dvec3 position{0.0};
    dmat3 rotation{1.0};

    dvec3 apply(const dvec3& p) const { return position + rotation * p; }
    /// World to body frame.
    dvec3 applyInverse(const dvec3& p) const { return glm::transpose(rotation) * (p - position); }
};

struct ManifoldPoint {
    dvec3 anchorA{0.0};   ///< the point on A's surface, in A's body frame
    dvec3 anchorB{0.0};   ///< the point on B's surface, in B's body frame
    dvec3 point{0.0};     ///< world, midway between the two surface points
    double separation = 0.0; ///< along the normal from A's surface to B's: negative when overlapping
    std::uint32_t id = 0;    ///< the pair of features that touch here (makeFeatureId)
};

struct Manifold {
    static constexpr int kMaxPoints = 4;
    dvec3 normal{0.0, 1.0, 0.0}; ///< world, unit, from A towards B
    int count = 0;               ///< 0: the shapes are further apart than the margin asked
    std::array<ManifoldPoint, kMaxPoints> points{};
};

/// A feature id from the two features' kinds and indices (a face, an edge or a vertex of each
/// shape): equal ids mean the same two features touch.
enum class Feature : std::uint32_t { Vertex = 0, Edge = 1, Face = 2 };
constexpr std::uint32_t makeFeatureId(Feature kindA, std::uint32_t indexA, Feature kindB, std::uint32_t indexB)
{
    return (static_cast<std::uint32_t>(kindA) << 30) | ((indexA & 0x3fffu) << 16) |
           (static_cast<std::uint32_t>(kindB) << 14) | (indexB & 0x3fffu);
}

} // namespace pba::contact
