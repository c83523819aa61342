#pragma once
// The contact rule of two balls, one for every kind of ball: a swarm's grains (in float, equal
// masses) and particles with a radius (in double, each its own mass and size). Private to the core.
//
// A pair is solved over a step's sweeps as sequential impulses (Box2D's), in positions and in
// speeds. Positions: the overlap is undone along the normal, each ball moved in proportion to
// its inverse mass; then static friction takes back how far the balls have slid over each other
// since they met (the pair's anchor, remembered from step to step, as the discrete element
// method's tangential spring of Cundall and Strack, and PhysX's anchored friction), by at most
// what mu times the pair's normal speed change moves them in a step. Without that memory each
// step's pushes apart along slanted normals, within the cone in any one step, added up: a heap
// crept outwards for as long as it stood. Speeds: the normal change accumulated over the sweeps
// stays a push that leaves the pair apart at restitution times its approach (none in resting
// contact), and the accumulated change of their sliding stays within mu times it.
#include <algorithm>
#include <cmath>
#include <limits>

#include "pba/math.hpp"

namespace pba::detail {

/// What a pair's contact has done over the step's sweeps so far: the change of the balls'
/// relative normal and sliding speeds (m/s) and the rebound it owes them; where its static
/// friction holds b against a (how far b has slid over a since they met, less where b was from a
/// then: b - a now added, the slip now), and how far the sweeps have taken the slip back this step.
template <class T>
struct BallContact {
    T normal = T(0), bounce = T(0);
    Vec3<T> tangent{T(0)};
    Vec3<T> anchor{T(0)};
    T held = T(0);
};

/// What one pair's rule needs: their radii's sum, each ball's share of a relative move or speed
/// change (its inverse mass over the pair's), and the contact's material and step.
template <class T>
struct BallPairRule {
    T reach = T(0);
    T shareA = T(0.5), shareB = T(0.5);
    T cor = T(0), friction = T(0);
    T restingSpeed = T(0); ///< below twice this an approach is resting contact: no rebound
    T dt = T(0);
};

/// Two balls touch while their centres are less than this many of their reaches apart: a pair
/// that an earlier sweep put exactly at contact still takes away the approach that later pairs
/// gave it (a ball pressed down from above onto one it rests on), or a heap's balls keep a speed
/// into each other, and sink.
inline constexpr double kBallsTouching = 1.01;

/// The longest slip of a contact that its static friction holds, in reaches: past it the contact
/// is sliding (kinetic friction), and its memory of where it began is dragged along at this
/// distance (as the discrete element method caps its tangential spring at mu times the normal
/// force), so that a ball stopping after a long slide is pulled back by at most this.
inline constexpr double kMostSlip = 0.01;

/// A contact's slip as the next step remembers it: at most kMostSlip reaches.
template <class T>
Vec3<T> rememberedSlip(const Vec3<T>& slip, T reach)
{
    const T length = glm::length(slip), most = T(kMostSlip) * reach;
    return length > most ? (most / length) * slip : slip;
}

/// What static friction takes back of a contact's slip `along` its surface: all of it, or `most`
/// of it (m), the length taken added to what it has `held` this step; nothing once the slip is
/// longer than `kinetic` (sliding).
template <class T>
Vec3<T> takenBack(const Vec3<T>& along, T most, T& held, T kinetic)
{
    const T length = glm::length(along);
    const T taken = std::min(length, most);
    if (!(taken > T(0)) || length > kinetic)
        return Vec3<T>(T(0));
    held += taken;
    return (taken / length) * along;
}

/// One pair's share of a sweep; `first`: the step's first sweep, which decides the rebound.
/// Inlined into the sweeps' loops: a call each pair cost a granular step about 1%.
template <class T>
[[gnu::always_inline]] inline void touchBalls(Vec3<T>& xa, Vec3<T>& va, Vec3<T>& xb, Vec3<T>& vb, BallContact<T>& pair,
                                              const BallPairRule<T> rule, bool first)
{
    const Vec3<T> d = xb - xa;
    const T d2 = glm::dot(d, d);
    if (!(d2 < T(kBallsTouching) * T(kBallsTouching) * rule.reach * rule.reach))
        return;
    const T distance = std::sqrt(d2);
    const Vec3<T> n = distance > T(0) ? d / distance : Vec3<T>(T(0), T(1), T(0)); // two at one point: one above
    const T overlap = std::max(T(0), rule.reach - distance);
    xa -= (rule.shareA * overlap) * n;
    xb += (rule.shareB * overlap) * n;
    // Static friction: b is taken back to where it began on a.
    if (const T most = rule.friction * pair.normal * rule.dt - pair.held; most > T(0)) {
        const Vec3<T> slip = pair.anchor + (xb - xa);
        const Vec3<T> back = takenBack(Vec3<T>(slip - glm::dot(slip, n) * n), most, pair.held, T(kMostSlip) * rule.reach);
        xa += rule.shareA * back;
        xb -= rule.shareB * back;
    }
    const Vec3<T> relative = vb - va;
    const T vn = glm::dot(relative, n);
    if (first)
        pair.bounce = -vn > T(2) * rule.restingSpeed ? -rule.cor * vn : T(0);
    const T normal = std::max(pair.normal + pair.bounce - vn, T(0));
    const T dvn = normal - pair.normal;
    pair.normal = normal;
    va -= (rule.shareA * dvn) * n;
    vb += (rule.shareB * dvn) * n;
    if (rule.friction > T(0)) {
        Vec3<T> tangent = pair.tangent - (relative - vn * n);
        const T most = rule.friction * pair.normal, length = glm::length(tangent);
        if (length > most)
            tangent *= most / length;
        const Vec3<T> dvt = tangent - pair.tangent;
        pair.tangent = tangent;
        va -= rule.shareA * dvt;
        vb += rule.shareB * dvt;
    }
}

/// A contact the balls make now, `d` their b - a: no impulses yet, and no slip (its anchor
/// where b is from a).
template <class T>
BallContact<T> newContact(const Vec3<T>& d)
{
    BallContact<T> c;
    c.anchor = -d;
    return c;
}

/// A contact's state as the next step starts it: its impulses, and its anchor from the slip it
/// ended with (`d` the pair's b - a at the end).
template <class T>
BallContact<T> carriedOver(const BallContact<T>& c, const Vec3<T>& d, T reach)
{
    const Vec3<T> n = d / std::max(glm::length(d), std::numeric_limits<T>::min());
    const Vec3<T> slip = c.anchor + d;
    BallContact<T> next;
    next.normal = c.normal;
    next.tangent = c.tangent;
    next.anchor = rememberedSlip(Vec3<T>(slip - glm::dot(slip, n) * n), reach) - d;
    return next;
}

} // namespace pba::detail
