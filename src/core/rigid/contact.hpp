#pragma once
// A contact between two rigid bodies, or between a body and the room, as the contact cache keeps
// it from step to step and the solver works on it: up to four points, each with the impulses it
// ended the last step with (warm starting, as Box2D and Jolt do).
#include <array>
#include <cstdint>

#include "contact/manifold.hpp"
#include "contact/narrow_phase.hpp"
#include "pba/math.hpp"

namespace pba::rigid {

/// Body indices are the rigid system's; the room's surfaces come after its bodies, so a contact
/// with the floor is a contact with one more (static) body.
using BodyIndex = std::uint32_t;

struct ContactPoint {
    dvec3 normal{0.0};   ///< world, unit, from A towards B (per point: the hole's shaft is round)
    dvec3 anchorA{0.0};  ///< on A's surface, A's frame
    dvec3 anchorB{0.0};  ///< on B's surface, B's frame (the world's for the room)
    dvec3 point{0.0};    ///< world, at the start of the step
    double separation = 0.0; ///< at the start of the step; negative when overlapping
    std::uint32_t id = 0;    ///< the features that touch (contact::makeFeatureId)
    double normalImpulse = 0.0;
    double tangentImpulse[2] = {0.0, 0.0};
    bool bounced = false; ///< took a restitution impulse this step (not warm-started next)
};

/// Where B was in A's frame when the narrow phase last ran on a pair of polyhedra, with what it
/// found: a pair that has hardly moved since carries its points over (carried_manifold.hpp).
struct PairPose {
    dvec3 offset{0.0};              ///< B's centre, A's frame
    dquat turn{1.0, 0.0, 0.0, 0.0}; ///< B's orientation, A's frame
    dvec3 normal{0.0};              ///< the manifold's normal, A's frame
    double margin = -1.0;           ///< the margin it looked within; negative: nothing to carry
};

struct Contact {
    BodyIndex a = 0, b = 0; ///< a < b; b may be a room surface
    double friction = 0.0;
    double restitution = 0.0;
    /// A sphere's radius, 0 for any other shape: a sphere's contact point is always its centre
    /// plus its radius along the normal, however it has spun since its anchor was taken.
    double radiusA = 0.0, radiusB = 0.0;
    int count = 0;
    std::array<ContactPoint, contact::Manifold::kMaxPoints> points{};
    contact::SatCache sat; ///< the narrow phase's memory of the pair's separating axis
    PairPose found;

    std::uint64_t key() const { return (std::uint64_t(a) << 32) | b; }
    /// The narrow phase's points, with no impulses yet.
    void takePoints(const contact::Manifold& m)
    {
        count = m.count;
        for (int i = 0; i < m.count; ++i) {
            ContactPoint& q = points[i];
            q = ContactPoint{};
            q.normal = m.normal;
            q.anchorA = m.points[i].anchorA;
            q.anchorB = m.points[i].anchorB;
            q.point = m.points[i].point;
            q.separation = m.points[i].separation;
            q.id = m.points[i].id;
        }
    }
};

} // namespace pba::rigid
