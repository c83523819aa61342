#include "rigid/carried_manifold.hpp"

#include <algorithm>
#include <cmath>

namespace pba::rigid {

PairPose pairPose(const contact::Transform& ta, const dquat& qa, const dvec3& xb, const dquat& qb,
                  const dvec3& worldNormal, double margin)
{
    PairPose pose;
    pose.offset = ta.applyInverse(xb);
    pose.turn = glm::conjugate(qa) * qb;
    pose.normal = glm::transpose(ta.rotation) * worldNormal;
    pose.margin = margin;
    return pose;
}

bool carryManifold(const Contact& from, const contact::Transform& ta, const dquat& qa, const contact::Transform& tb,
                   const dquat& qb, double radiusB, double margin, Contact& to)
{
    const PairPose& found = from.found;
    if (found.margin < margin)
        return false;
    const dvec3 offset = ta.applyInverse(tb.position);
    // The turn between the two relative orientations: sin of half its angle is the length of the
    // vector part of found.turn^-1 * turn, that is sqrt(1 - dot^2).
    const double dot = std::min(1.0, std::abs(glm::dot(found.turn, glm::conjugate(qa) * qb)));
    const double angle = 2.0 * std::sqrt(std::max(0.0, 1.0 - dot * dot));
    if (glm::length(offset - found.offset) + angle * radiusB > kCarryDistance)
        return false;
    const dvec3 n = ta.rotation * found.normal;
    to.count = 0;
    for (int i = 0; i < from.count; ++i) {
        const ContactPoint& p = from.points[i];
        const dvec3 pa = ta.apply(p.anchorA);
        const dvec3 pb = tb.apply(p.anchorB);
        const double separation = glm::dot(n, pb - pa);
        if (separation > margin)
            continue;
        ContactPoint& q = to.points[to.count++];
        q = ContactPoint{};
        q.normal = n;
        q.anchorA = p.anchorA;
        q.anchorB = p.anchorB;
        q.point = 0.5 * (pa + pb);
        q.separation = separation;
        q.id = p.id;
    }
    to.found = found;
    return true;
}

} // namespace pba::rigid
