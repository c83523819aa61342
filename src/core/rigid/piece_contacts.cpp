#include "rigid/piece_contacts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "contact/sphere_contact.hpp"
#include "balls/piece_geometry.hpp"

namespace pba::rigid {

namespace {

using contact::CollisionShape;
using contact::Transform;

/// The point of the segment from pa to pb closest to c.
dvec3 closestOnSegment(const dvec3& pa, const dvec3& pb, const dvec3& c)
{
    const dvec3 d = pb - pa;
    const double length2 = glm::dot(d, d);
    const double t = length2 > 0.0 ? std::clamp(glm::dot(c - pa, d) / length2, 0.0, 1.0) : 0.0;
    return pa + t * d;
}

/// What an impulse along u at arm r does to the body's point there, along u.
double inverseMassAlong(const SolverBody& body, const dvec3& r, const dvec3& u)
{
    const dvec3 c = glm::cross(r, u);
    return body.inverseMass + glm::dot(c, body.inverseInertia * c);
}

/// The piece's point of contact c as the solver sees it: its velocity, and its inverse mass
/// along u (each ball moves by its weight of the point's impulse, and carries that share of it:
/// a piece without mass between them).
struct PiecePoint {
    const PieceContact& c;
    std::span<SolverBody> bodies;
    dvec3 relativeVelocity() const
    {
        dvec3 v(0.0);
        for (std::size_t e = 0; e < 3; ++e)
            v += c.weights[e] * bodies[c.ends[e]].v;
        return v - bodies[c.body].pointVelocity(c.arm);
    }
    double inverseMass(const dvec3& u) const
    {
        double w = 0.0;
        for (std::size_t e = 0; e < 3; ++e)
            w += c.weights[e] * c.weights[e] * bodies[c.ends[e]].inverseMass;
        return w + inverseMassAlong(bodies[c.body], c.arm, u);
    }
    /// An impulse p on the piece's point (-p on the body), on the end velocities, and on the
    /// end poses by the share of the step's drift the end velocity drives (as moveEndPoses).
    void applyImpulse(const dvec3& p, double dt) const
    {
        for (std::size_t e = 0; e < 3; ++e)
            if (SolverBody& ball = bodies[c.ends[e]]; !ball.isStatic()) {
                const double share = c.weights[e];
                const dvec3 dv = share * ball.inverseMass * p;
                ball.v += dv;
                ball.endPosition += ball.driftWeight * dt * dv;
            }
        if (SolverBody& body = bodies[c.body]; !body.isStatic()) {
            const dvec3 dv = -p * body.inverseMass;
            const dvec3 dw = body.inverseInertia * glm::cross(c.arm, -p);
            body.v += dv;
            body.w += dw;
            body.endPosition += body.driftWeight * dt * dv;
            body.endOrientation = turned(body.endOrientation, body.driftWeight * dt * dw);
        }
    }
    void movePoses(const dvec3& p) const
    {
        for (std::size_t e = 0; e < 3; ++e)
            if (SolverBody& ball = bodies[c.ends[e]]; !ball.isStatic())
                ball.endPosition += c.weights[e] * ball.inverseMass * p;
        bodies[c.body].movePose(-p, c.arm);
    }
    /// How far the point has moved towards the body along the normal since `from` (the balls'
    /// end positions, then the body's, when the contact was found).
    double approach(const std::array<dvec3, 4>& from) const
    {
        dvec3 moved(0.0);
        for (std::size_t e = 0; e < 3; ++e)
            moved += c.weights[e] * (bodies[c.ends[e]].endPosition - from[e]);
        moved -= bodies[c.body].endPosition - from[3];
        return -glm::dot(moved, c.normal);
    }
};

/// A ball of radius r at c against `shape` at `pose`, at any distance: one point.
contact::Manifold ballAgainst(const CollisionShape& shape, const Transform& pose, const dvec3& c, double r)
{
    const Transform at{c, dmat3(1.0)};
    if (shape.kind == CollisionShape::Kind::Sphere)
        return contact::sphereSphere(shape.radius, pose, r, at, INFINITY);
    return contact::polyhedronSphere(*shape.polyhedron, pose, r, at, INFINITY);
}

/// Where f, concave on [0, 1], is largest: a golden-section search, each round narrowing the
/// bracket to 0.618 of itself.
template <class F>
double largestOfConcave(const F& f, int rounds)
{
    constexpr double kRatio = 0.6180339887498949; // 1 / the golden ratio
    double lo = 0.0, hi = 1.0;
    double t1 = hi - kRatio * (hi - lo), t2 = lo + kRatio * (hi - lo);
    double f1 = f(t1), f2 = f(t2);
    for (int round = 0; round < rounds; ++round) {
        if (f1 < f2) {
            lo = t1;
            t1 = t2;
            f1 = f2;
            t2 = lo + kRatio * (hi - lo);
            f2 = f(t2);
        } else {
            hi = t2;
            t2 = t1;
            f2 = f1;
            t1 = hi - kRatio * (hi - lo);
            f1 = f(t1);
        }
    }
    return f1 < f2 ? t2 : t1;
}

/// Where between `outer` (where below(t) is false) and `inner` (true) it turns, by halving.
template <class Below>
double edgeOf(const Below& below, double outer, double inner, int halvings)
{
    for (int it = 0; it < halvings; ++it) {
        const double middle = 0.5 * (outer + inner);
        (below(middle) ? inner : outer) = middle;
    }
    return inner;
}

} // namespace

SegmentDepths deepestBetweenBalls(const CollisionShape& shape, const Transform& pose, const dvec3& pa, double ra,
                                  const dvec3& pb, double rb, double margin)
{
    // As thick as its balls, but no thicker than the piece's rule allows.
    const double length = glm::length(pb - pa);
    const double thickest = detail::thickestPiece(std::array{pa, pb}, std::array{ra, rb});
    if (!(thickest > 0.0))
        return {};
    const auto radius = [&](double t) { return std::min(ra + t * (rb - ra), thickest); };
    const dvec3 nearest = closestOnSegment(pa, pb, pose.position);
    if (glm::length(nearest - pose.position) > shape.boundingRadius() + std::max(ra, rb))
        return {};
    const auto pointAt = [&](double t) { return pa + t * (pb - pa); };
    const auto separation = [&](double t) { return ballAgainst(shape, pose, pointAt(t), radius(t)).points[0].separation; };
    const contact::Manifold ma = ballAgainst(shape, pose, pa, radius(0.0)), mb = ballAgainst(shape, pose, pb, radius(1.0));
    const double sa = ma.points[0].separation, sb = mb.points[0].separation;
    // Both centres above one face of a polyhedron, over it: the segment lies in the prism over
    // the face (convex), where its separation is linear, level with its balls' line.
    const auto overFace = [&](const contact::Manifold& m, double r) {
        return (m.points[0].id >> 30) == std::uint32_t(contact::Feature::Face) && m.points[0].separation + r > 0.0;
    };
    if (shape.kind == CollisionShape::Kind::Polyhedron && ma.points[0].id == mb.points[0].id &&
        overFace(ma, radius(0.0)) && overFace(mb, radius(1.0)))
        return {};
    // No point of the segment is nearer the shape than its ends' distances less its distance to
    // them: when those add up to more than its length, none of it can touch.
    if (sa + sb > length + 2.0 * margin)
        return {};
    // How much deeper than the balls' line the segment lies at t: concave (a convex shape's
    // distance is convex along a line), 0 at both ends, and so nowhere above twice its middle's
    // (a segment lying along a face is level with its balls).
    const auto beyond = [&](double t) { return sa + t * (sb - sa) - separation(t); };
    if (!(beyond(0.5) > 0.5 * detail::kPieceLevel))
        return {};
    // Where it comes nearest the shape, its separation being convex along it: a golden-section
    // search of 16 rounds finds that to a four-thousandth of the segment (30 um of a cloth's 13
    // cm). Not where it lies deepest beyond its balls' line: a segment from a ball just above a
    // bar to one hanging far below it has that point at the bar's far corner, clear of it, while
    // it cuts the near one.
    const double deepest = largestOfConcave([&](double t) { return -separation(t); }, 16);
    // A segment lying across a face (its middle on a box's top, its balls beyond the edges) is
    // as near along a stretch, where the line of its balls may tilt either way: held at one
    // point of it, it would be held at one end of the stretch or the other from step to step and
    // rock. It is held at both ends instead, as a box lying on a face is at its corners. The
    // stretch is where its separation is within 10 um of the nearest point's (a convex function's
    // level set: bisection finds each end): resting there, the segment tilts by a few microns
    // either way from step to step.
    constexpr double kFlat = 1e-5;
    const double level = separation(deepest) + kFlat;
    const auto onLevel = [&](double t) { return separation(t) <= level; };
    constexpr double kStretch = 0.01; // of the segment: shorter, a point
    // (A stretch reaches at least one of the two points half of kStretch away: the search may
    // stop at either end of it. Only then are its ends looked for.)
    const bool flat = onLevel(std::max(deepest - 0.5 * kStretch, 0.0)) || onLevel(std::min(deepest + 0.5 * kStretch, 1.0));
    constexpr int kHalvings = 12;
    const double first = flat ? edgeOf(onLevel, 0.0, deepest, kHalvings) : deepest;
    const double last = flat ? edgeOf(onLevel, 1.0, deepest, kHalvings) : deepest;
    // A point nearest at one of the balls, within the search's reach, is that ball's own contact.
    const bool atABall = deepest < 0.5 * kStretch || deepest > 1.0 - 0.5 * kStretch;
    SegmentDepths out;
    for (const double t : last - first > kStretch ? std::array{first, last}
                          : atABall               ? std::array{-1.0, -1.0}
                                                  : std::array{deepest, -1.0}) {
        if (t < 0.0)
            continue;
        const contact::Manifold m = ballAgainst(shape, pose, pointAt(t), radius(t));
        const double s = m.points[0].separation;
        const double line = sa + t * (sb - sa);
        if (s < margin && line - s > detail::kPieceLevel)
            out.points[std::size_t(out.count++)] = SegmentDepth{t, m.normal, pointAt(t), s, line};
    }
    return out;
}

std::optional<TriangleDepth> deepestUnderTriangle(const CollisionShape& shape, const Transform& pose,
                                                  const std::array<dvec3, 3>& x, const std::array<double, 3>& r,
                                                  double margin)
{
    const dvec3 e1 = x[1] - x[0], e2 = x[2] - x[0];
    const dvec3 across = glm::cross(e1, e2);
    const double twiceArea = glm::length(across);
    if (!(twiceArea > 0.0))
        return std::nullopt;
    const double thickest = detail::thickestPiece(x, r);
    if (!(thickest > 0.0))
        return std::nullopt;
    // From the shape towards the triangle: away from the side its centre is on.
    dvec3 normal = across / twiceArea;
    if (glm::dot(pose.position - x[0], normal) > 0.0)
        normal = -normal;
    if (std::abs(glm::dot(pose.position - x[0], normal)) > shape.boundingRadius() + thickest + margin)
        return std::nullopt;
    std::optional<TriangleDepth> best;
    const auto consider = [&](const dvec3& p) {
        // Over the inside, away from the sides (the segments hold those).
        std::array<double, 3> w{};
        if (!detail::footOnPiece(p, x, w))
            return;
        const double thickness = std::min(w[0] * r[0] + w[1] * r[1] + w[2] * r[2], thickest);
        const double separation = glm::dot(x[0] - p, normal) - thickness;
        // A point further through than the triangle is thick is no point of it: the body's
        // plane section lies beside the triangle (a sheet's half-cell tilted over a box's edge
        // has the box's far corner over it, beyond its plane).
        if (separation < -2.0 * thickness)
            return;
        if (separation < margin && (!best || separation < best->separation))
            best = TriangleDepth{w, normal, p, separation, 0.0};
    };
    if (shape.kind == CollisionShape::Kind::Sphere)
        consider(pose.position + shape.radius * normal);
    else
        for (const dvec3& vertex : shape.polyhedron->vertices)
            consider(pose.apply(vertex));
    if (!best)
        return std::nullopt;
    // Deeper than its balls' own separations there, or their contacts hold it (a sheet lying on
    // a face is level with its balls).
    for (std::size_t e = 0; e < 3; ++e)
        best->line += best->weights[e] * ballAgainst(shape, pose, x[e], r[e]).points[0].separation;
    if (!(best->line - best->separation > detail::kPieceLevel))
        return std::nullopt;
    return best;
}

void holdPieces(std::span<const PieceContact> contacts, std::span<SolverBody> bodies, double restingSpeed,
                  double dt, int sweeps)
{
    struct Held {
        double normal = 0.0;   ///< the normal impulse so far
        dvec3 friction{0.0};   ///< the friction impulse so far
        double target = 0.0;   ///< the normal speed it leaves with
        std::array<dvec3, 4> from{}; ///< the ends' and the body's end positions at the start
    };
    thread_local std::vector<Held> held;
    held.assign(contacts.size(), Held{});
    for (std::size_t k = 0; k < contacts.size(); ++k) {
        const PieceContact& c = contacts[k];
        const PiecePoint p{c, bodies};
        const double arriving = glm::dot(p.relativeVelocity(), c.normal);
        held[k].target = c.gap > 0.0                 ? -c.gap / dt
                         : arriving < -restingSpeed ? -c.restitution * arriving
                                                    : 0.0;
        for (std::size_t e = 0; e < 3; ++e)
            held[k].from[e] = bodies[c.ends[e]].endPosition;
        held[k].from[3] = bodies[c.body].endPosition;
    }
    for (int sweep = 0; sweep < sweeps; ++sweep)
        for (std::size_t k = 0; k < contacts.size(); ++k) {
            const PieceContact& c = contacts[k];
            const PiecePoint p{c, bodies};
            if (!(p.inverseMass(c.normal) > 0.0)) // fixed balls on a fixed body
                continue;
            Held& h = held[k];
            const double normal =
                std::max(0.0, h.normal + (h.target - glm::dot(p.relativeVelocity(), c.normal)) / p.inverseMass(c.normal));
            p.applyImpulse((normal - h.normal) * c.normal, dt);
            h.normal = normal;
            const dvec3 v = p.relativeVelocity();
            const dvec3 slip = v - glm::dot(v, c.normal) * c.normal;
            const double speed = glm::length(slip);
            if (!(speed > 0.0))
                continue;
            dvec3 friction = h.friction - slip / p.inverseMass(slip / speed);
            const double most = c.friction * h.normal;
            if (const double size = glm::length(friction); size > most)
                friction *= most / size;
            p.applyImpulse(friction - h.friction, dt);
            h.friction = friction;
        }
    for (int sweep = 0; sweep < sweeps; ++sweep)
        for (std::size_t k = 0; k < contacts.size(); ++k) {
            const PieceContact& c = contacts[k];
            const PiecePoint p{c, bodies};
            Held& h = held[k];
            const double left = c.depth + p.approach(h.from);
            if (!(left > 0.0) || !(p.inverseMass(c.normal) > 0.0))
                continue;
            p.movePoses(left / p.inverseMass(c.normal) * c.normal);
        }
}

} // namespace pba::rigid
