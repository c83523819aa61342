// The narrow phase: contact manifolds between spheres, boxes, prisms and hulls, against cases
// worked by hand (each derivation beside its test) and, for random box pairs, against an
// independent measurement of each point's separation (where the line along the normal leaves
// one box and enters the other, by the slab method).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include "core/contact/narrow_phase.hpp"
#include "core/contact/polyhedron_contact.hpp"
#include "pba/overlap.hpp"

namespace {

using namespace pba::contact;
using pba::dmat3;
using pba::dvec3;
using pba::Shape;

constexpr double kSqrt2 = std::numbers::sqrt2;

dmat3 rotation(double degrees, const dvec3& axis)
{
    return glm::mat3_cast(glm::angleAxis(degrees * std::numbers::pi / 180.0, glm::normalize(axis)));
}

Transform pose(const dvec3& position, const dmat3& r = dmat3(1.0))
{
    return {position, r};
}

CollisionShape box(const dvec3& size)
{
    return CollisionShape::of(Shape::box(size));
}

std::uint32_t kindA(std::uint32_t id)
{
    return id >> 30;
}
std::uint32_t kindB(std::uint32_t id)
{
    return (id >> 14) & 3u;
}

void expectNear(const dvec3& actual, const dvec3& expected, double tolerance)
{
    EXPECT_LT(glm::length(actual - expected), tolerance) << "got (" << actual.x << ", " << actual.y << ", " << actual.z
                                                         << "), expected (" << expected.x << ", " << expected.y << ", "
                                                         << expected.z << ")";
}

/// Every point's own consistency: its anchors are the surface points, its world point their
/// midpoint, and its separation their distance along the normal.
void expectConsistent(const Manifold& m, const Transform& ta, const Transform& tb)
{
    EXPECT_NEAR(glm::length(m.normal), 1.0, 1e-12);
    for (int k = 0; k < m.count; ++k) {
        const ManifoldPoint& p = m.points[static_cast<std::size_t>(k)];
        const dvec3 onA = ta.apply(p.anchorA), onB = tb.apply(p.anchorB);
        expectNear(p.point, 0.5 * (onA + onB), 1e-12);
        EXPECT_NEAR(glm::dot(m.normal, onB - onA), p.separation, 1e-12);
    }
}

// A 1 m cube rests centred off-axis on a 2 x 1 x 2 slab whose top is y = 0.5: the cube's bottom
// face (y = 0.5) lies inside the slab's top, so the slab's top face is the reference and the
// cube's four bottom corners, (0.2 +- 0.5, 0.5, -0.1 +- 0.5), are the points, at separation 0,
// the normal straight up.
TEST(NarrowPhase, BoxRestingOnBoxHasFourCornersAtSeparationZero)
{
    const CollisionShape slab = box({2, 1, 2}), cube = box({1, 1, 1});
    const Transform ta = pose({0, 0, 0}), tb = pose({0.2, 1.0, -0.1});
    const Manifold m = collide(slab, ta, cube, tb, 0.01);
    ASSERT_EQ(m.count, 4);
    expectNear(m.normal, {0, 1, 0}, 1e-15);
    std::set<std::uint32_t> ids;
    for (int k = 0; k < 4; ++k) {
        const ManifoldPoint& p = m.points[static_cast<std::size_t>(k)];
        EXPECT_NEAR(p.separation, 0.0, 1e-15);
        EXPECT_NEAR(std::abs(p.point.x - 0.2), 0.5, 1e-15);
        EXPECT_NEAR(p.point.y, 0.5, 1e-15);
        EXPECT_NEAR(std::abs(p.point.z + 0.1), 0.5, 1e-15);
        expectNear(p.anchorB, dvec3(std::copysign(0.5, p.anchorB.x), -0.5, std::copysign(0.5, p.anchorB.z)), 1e-15);
        EXPECT_EQ(kindA(p.id), static_cast<std::uint32_t>(Feature::Face));
        EXPECT_EQ(kindB(p.id), static_cast<std::uint32_t>(Feature::Vertex));
        ids.insert(p.id);
    }
    EXPECT_EQ(ids.size(), 4u);
    expectConsistent(m, ta, tb);
}

// The contact cache matches points by id: nudged by a micrometre (along, up, or turned), the
// same corners touch the same face, so the ids come back the same and in the same order.
TEST(NarrowPhase, RestingBoxKeepsItsIdsWhenNudgedByAMicrometre)
{
    const CollisionShape slab = box({2, 1, 2}), cube = box({1, 1, 1});
    const Transform ta = pose({0, 0, 0});
    const Manifold before = collide(slab, ta, cube, pose({0.2, 1.0, -0.1}), 0.01);
    for (const Transform& tb : {pose({0.2 + 1e-6, 1.0, -0.1 - 1e-6}), pose({0.2, 1.0 + 1e-6, -0.1}),
                                pose({0.2, 1.0 - 1e-6, -0.1}), pose({0.2, 1.0, -0.1}, rotation(1e-4, {1, 2, 3}))}) {
        const Manifold after = collide(slab, ta, cube, tb, 0.01);
        ASSERT_EQ(after.count, before.count);
        for (int k = 0; k < after.count; ++k)
            EXPECT_EQ(after.points[static_cast<std::size_t>(k)].id, before.points[static_cast<std::size_t>(k)].id);
    }
}

// A unit cube (half side h = 0.5) turned 45 degrees about x, then 45 about z: its corner
// (x, y, z) sits at height x / sqrt 2 + (y - z) / 2 about its centre, lowest at (-h, -h, h), at
// -h (1 + 1 / sqrt 2); the next lowest, (h, -h, h), is sqrt 2 h higher. Its centre at
// 0.5 + h (1 + 1 / sqrt 2) - d puts that corner d below the slab's top (y = 0.5): one point, the
// normal up, the separation -d.
TEST(NarrowPhase, CornerOfATurnedCubeOnAFace)
{
    const double h = 0.5, d = 0.01;
    const dmat3 r = rotation(45, {0, 0, 1}) * rotation(45, {1, 0, 0});
    const CollisionShape slab = box({4, 1, 4}), cube = box({1, 1, 1});
    const Transform ta = pose({0, 0, 0}), tb = pose({0.1, 0.5 + h * (1 + 1 / kSqrt2) - d, 0.2}, r);
    const Manifold m = collide(slab, ta, cube, tb, 0.02);
    ASSERT_EQ(m.count, 1);
    expectNear(m.normal, {0, 1, 0}, 1e-12);
    const ManifoldPoint& p = m.points[0];
    EXPECT_NEAR(p.separation, -d, 1e-12);
    expectNear(p.anchorB, {-h, -h, h}, 1e-12);
    const dvec3 corner = tb.apply({-h, -h, h});
    EXPECT_NEAR(corner.y, 0.5 - d, 1e-12);
    expectNear(p.anchorA, {corner.x, 0.5, corner.z}, 1e-12);
    EXPECT_EQ(kindA(p.id), static_cast<std::uint32_t>(Feature::Face));
    EXPECT_EQ(kindB(p.id), static_cast<std::uint32_t>(Feature::Vertex));
    expectConsistent(m, ta, tb);
}

// Two unit cubes crossed: A turned 45 degrees about z has a ridge along z on top, at
// y = h sqrt 2 (its corner edge (h, h, z)); B turned 45 degrees about x has one along x
// underneath, at its centre's height less h sqrt 2 (its edge (x, -h, h)). B's centre at
// y = 2 h sqrt 2 - d makes the ridges cross d deep at (0, ., z_B): the normal is along z x x = y,
// the separation -d, the point midway, at height h sqrt 2 - d / 2. Every face axis leaves
// them (h + d) / sqrt 2 deep, far more than d: the edges win.
TEST(NarrowPhase, CrossedEdgesTouchOnTheirCommonNormal)
{
    const double h = 0.5, d = 0.02, zB = 0.1;
    const CollisionShape a = box({1, 1, 1}), b = box({1, 1, 1});
    const Transform ta = pose({0, 0, 0}, rotation(45, {0, 0, 1}));
    const Transform tb = pose({0.05, 2 * h * kSqrt2 - d, zB}, rotation(45, {1, 0, 0}));
    const Manifold m = collide(a, ta, b, tb, 0.0);
    ASSERT_EQ(m.count, 1);
    expectNear(m.normal, {0, 1, 0}, 1e-12);
    const ManifoldPoint& p = m.points[0];
    EXPECT_NEAR(p.separation, -d, 1e-12);
    expectNear(p.point, {0, h * kSqrt2 - d / 2, zB}, 1e-12);
    expectNear(p.anchorA, {h, h, zB}, 1e-12);
    expectNear(p.anchorB, {-0.05, -h, h}, 1e-12);
    EXPECT_EQ(kindA(p.id), static_cast<std::uint32_t>(Feature::Edge));
    EXPECT_EQ(kindB(p.id), static_cast<std::uint32_t>(Feature::Edge));
    expectConsistent(m, ta, tb);
}

// A sphere of radius 0.25 against a 2 x 1 x 1.5 box (half extents 1, 0.5, 0.75). Over the top
// face, its centre 0.24 above the top leaves it 0.01 deep straight down. Beyond the edge
// (x = 1, y = 0.5) by a = 0.1 each way, the closest point is on that edge, sqrt 2 a away along
// (1, 1, 0) / sqrt 2; beyond the corner by a each way, the corner, sqrt 3 a away along
// (1, 1, 1) / sqrt 3.
TEST(NarrowPhase, SphereOnABoxFaceEdgeAndCorner)
{
    const CollisionShape slab = box({2, 1, 1.5}), ball = CollisionShape::of(Shape::sphere(0.25));
    const Transform ta = pose({0, 0, 0});
    struct Case {
        dvec3 centre, normal, onBox;
        double separation;
        Feature kind;
    };
    const double a = 0.1;
    for (const Case& c : {Case{{0.3, 0.74, 0.2}, {0, 1, 0}, {0.3, 0.5, 0.2}, -0.01, Feature::Face},
                          Case{{1 + a, 0.5 + a, 0.2}, dvec3(1, 1, 0) / kSqrt2, {1, 0.5, 0.2}, kSqrt2 * a - 0.25, Feature::Edge},
                          Case{{1 + a, 0.5 + a, 0.75 + a}, dvec3(1.0) / std::sqrt(3.0), {1, 0.5, 0.75},
                               std::sqrt(3.0) * a - 0.25, Feature::Vertex}}) {
        const Transform tb = pose(c.centre, rotation(30, {1, 1, 0}));
        const Manifold m = collide(slab, ta, ball, tb, 0.0);
        ASSERT_EQ(m.count, 1);
        expectNear(m.normal, c.normal, 1e-12);
        EXPECT_NEAR(m.points[0].separation, c.separation, 1e-12);
        expectNear(m.points[0].anchorA, c.onBox, 1e-12);
        EXPECT_EQ(kindA(m.points[0].id), static_cast<std::uint32_t>(c.kind));
        expectConsistent(m, ta, tb);
    }
}

// A centre inside the box leaves through the face it is least deep below: at (0.9, 0.1, 0) in
// the same box that is +x (0.1 below it; +y is 0.4 below), so the normal is +x and the sphere
// is 0.1 + 0.25 deep.
TEST(NarrowPhase, SphereCentreInsideABoxLeavesByTheNearestFace)
{
    const Manifold m = collide(box({2, 1, 1.5}), pose({0, 0, 0}), CollisionShape::of(Shape::sphere(0.25)),
                               pose({0.9, 0.1, 0}), 0.0);
    ASSERT_EQ(m.count, 1);
    expectNear(m.normal, {1, 0, 0}, 1e-15);
    EXPECT_NEAR(m.points[0].separation, -0.35, 1e-15);
    expectNear(m.points[0].anchorA, {1, 0.1, 0}, 1e-15);
}

// Radii 0.5 and 0.3, centres (6, 2, 3) / 10 apart: 0.7 (a 2-3-6-7 quadruple), so 0.1 deep along
// (6, 2, 3) / 7. The anchors are in each sphere's own (turned) frame.
TEST(NarrowPhase, SphereSphereAlongTheLineOfCentres)
{
    const Transform ta = pose({1, 2, 3}, rotation(40, {0, 1, 1})), tb = pose({1.6, 2.2, 3.3}, rotation(-70, {1, 0, 0}));
    const Manifold m =
        collide(CollisionShape::of(Shape::sphere(0.5)), ta, CollisionShape::of(Shape::sphere(0.3)), tb, 0.0);
    ASSERT_EQ(m.count, 1);
    const dvec3 n = dvec3(6, 2, 3) / 7.0;
    expectNear(m.normal, n, 1e-12);
    EXPECT_NEAR(m.points[0].separation, -0.1, 1e-12);
    expectNear(ta.apply(m.points[0].anchorA), ta.position + 0.5 * n, 1e-12);
    expectNear(tb.apply(m.points[0].anchorB), tb.position - 0.3 * n, 1e-12);
    expectConsistent(m, ta, tb);
    // 0.7 apart is 0.1 beyond touching radii of 0.3 and 0.3: inside a margin of 0.15, not 0.05.
    const CollisionShape small = CollisionShape::of(Shape::sphere(0.3));
    EXPECT_EQ(collide(small, ta, small, tb, 0.15).count, 1);
    EXPECT_EQ(collide(small, ta, small, tb, 0.05).count, 0);
}

/// Twice the area of the convex quadrilateral the points make (in the plane y = const).
double quadArea2(const Manifold& m)
{
    std::vector<dvec3> p;
    for (int k = 0; k < m.count; ++k)
        p.push_back(m.points[static_cast<std::size_t>(k)].point);
    dvec3 c(0.0);
    for (const dvec3& v : p)
        c += v / double(p.size());
    std::sort(p.begin(), p.end(), [&](const dvec3& u, const dvec3& v) {
        return std::atan2(u.z - c.z, u.x - c.x) < std::atan2(v.z - c.z, v.x - c.x);
    });
    double area = 0.0;
    for (std::size_t k = 0; k < p.size(); ++k)
        area += std::abs(glm::cross(p[k] - c, p[(k + 1) % p.size()] - c).y);
    return area;
}

// A cylinder (r = 0.5, as a prism of 24 sides) standing d deep in a slab: its bottom cap's 24
// corners all touch at -d and are reduced to four. The deepest ties, so the first is kept, then
// the corner opposite it (the diameter), then the corners furthest either side of that
// diameter, 90 degrees round (24 sides divide by 4): the inscribed square, of area 2 r^2.
TEST(NarrowPhase, StandingPrismKeepsTheSquareOfItsRim)
{
    const double r = 0.5, d = 0.003;
    const CollisionShape slab = box({4, 1, 4}), cylinder = CollisionShape::of(Shape::cylinder(r, 1.0));
    const Transform ta = pose({0, 0, 0}), tb = pose({0.3, 0.5 + 0.5 - d, -0.2});
    const Manifold m = collide(slab, ta, cylinder, tb, 0.01);
    ASSERT_EQ(m.count, 4);
    expectNear(m.normal, {0, 1, 0}, 1e-15);
    for (int k = 0; k < 4; ++k) {
        const ManifoldPoint& p = m.points[static_cast<std::size_t>(k)];
        EXPECT_NEAR(p.separation, -d, 1e-12);
        EXPECT_NEAR(std::hypot(p.anchorB.x, p.anchorB.z), r, 1e-12);
    }
    EXPECT_NEAR(quadArea2(m), 2 * 2 * r * r, 1e-12);
    expectConsistent(m, ta, tb);
}

// The same cylinder lying on its side (turned 90 degrees about x, its axis along z) rests on
// its rim edge at angle 90 degrees (vertex 6 of 24), which reaches r below its axis: the two
// side faces either side of it lean 7.5 degrees, their other edges 2 r sin^2(7.5) = 17 mm up,
// beyond a 1 cm margin. Two points, the rim edge's ends, at z = +-0.5 and -d.
TEST(NarrowPhase, LyingPrismTouchesAlongALine)
{
    const double r = 0.5, d = 0.002;
    const Transform ta = pose({0, 0, 0}), tb = pose({0, 0.5 + r - d, 0}, rotation(90, {1, 0, 0}));
    const Manifold m = collide(box({4, 1, 4}), ta, CollisionShape::of(Shape::cylinder(r, 1.0)), tb, 0.01);
    ASSERT_EQ(m.count, 2);
    expectNear(m.normal, {0, 1, 0}, 1e-15);
    for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(m.points[static_cast<std::size_t>(k)].separation, -d, 1e-12);
        EXPECT_NEAR(std::abs(m.points[static_cast<std::size_t>(k)].point.z), 0.5, 1e-12);
        EXPECT_NEAR(m.points[static_cast<std::size_t>(k)].point.x, 0.0, 1e-12);
    }
}

// A unit square on a unit square turned 45 degrees about the normal overlap in a regular-ish
// octagon (the square less four corner triangles with legs 1 - 1 / sqrt 2: area
// 1 - 2 (1 - 1 / sqrt 2)^2 = 0.828); its eight corners reduce to four spanning more than half
// of it, each a corner of the octagon.
TEST(NarrowPhase, EightClippedCornersReduceToFour)
{
    const Transform ta = pose({0, 0, 0}), tb = pose({0, 1, 0}, rotation(45, {0, 1, 0}));
    const Manifold m = collide(box({1, 1, 1}), ta, box({1, 1, 1}), tb, 0.0);
    ASSERT_EQ(m.count, 4);
    for (int k = 0; k < 4; ++k) {
        const dvec3& p = m.points[static_cast<std::size_t>(k)].point;
        EXPECT_NEAR(p.y, 0.5, 1e-12);
        // On the edge of one square or the other.
        const bool onA = std::abs(std::max(std::abs(p.x), std::abs(p.z)) - 0.5) < 1e-12;
        const bool onB = std::abs((std::abs(p.x) + std::abs(p.z)) / kSqrt2 - 0.5) < 1e-12;
        EXPECT_TRUE(onA && onB);
    }
    const double octagon = 1 - 2 * (1 - 1 / kSqrt2) * (1 - 1 / kSqrt2);
    EXPECT_GT(quadArea2(m) / 2, 0.5 * octagon);
    EXPECT_LE(quadArea2(m) / 2, octagon + 1e-12);
}

// 1 cm apart, a box resting over another is inside a 2 cm margin (four points at +0.01) and
// outside a 5 mm one (none).
TEST(NarrowPhase, MarginKeepsNearbyPointsAndDropsFurtherOnes)
{
    const CollisionShape slab = box({2, 1, 2}), cube = box({1, 1, 1});
    const Transform ta = pose({0, 0, 0}), tb = pose({0.2, 1.01, -0.1});
    const Manifold near = collide(slab, ta, cube, tb, 0.02);
    ASSERT_EQ(near.count, 4);
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(near.points[static_cast<std::size_t>(k)].separation, 0.01, 1e-12);
    EXPECT_EQ(collide(slab, ta, cube, tb, 0.005).count, 0);
    // The same for a sphere and for a corner: 1 cm is beyond 5 mm.
    const CollisionShape ball = CollisionShape::of(Shape::sphere(0.25));
    EXPECT_EQ(collide(slab, ta, ball, pose({0, 0.76, 0}), 0.02).count, 1);
    EXPECT_EQ(collide(slab, ta, ball, pose({0, 0.76, 0}), 0.005).count, 0);
}

/// Whether `m` seen from B (collide(b, a)) is `m` seen from A: the normal reversed, the same
/// points with the anchors exchanged and each id's halves (A's feature, B's) swapped.
void expectSwapped(const Manifold& ab, const Manifold& ba)
{
    ASSERT_EQ(ab.count, ba.count);
    expectNear(ba.normal, -ab.normal, 1e-12);
    for (int k = 0; k < ab.count; ++k) {
        const ManifoldPoint& p = ab.points[static_cast<std::size_t>(k)];
        const auto match = std::find_if(ba.points.begin(), ba.points.begin() + ba.count, [&](const ManifoldPoint& q) {
            return glm::length(q.point - p.point) < 1e-12;
        });
        ASSERT_NE(match, ba.points.begin() + ba.count) << "point " << k << " has no match";
        EXPECT_NEAR(match->separation, p.separation, 1e-12);
        expectNear(match->anchorA, p.anchorB, 1e-12);
        expectNear(match->anchorB, p.anchorA, 1e-12);
        EXPECT_EQ(match->id, (p.id >> 16) | (p.id << 16));
    }
}

// The reference face is chosen the same way whichever shape is A (the face that separates the
// shapes clearly further, or on a near tie the larger of the two), so each of these pairs
// (resting, corner on face, crossed edges, sphere on an edge, a standing prism whose 24 rim
// points reduce to 4) gives the same manifold seen from the other side.
TEST(NarrowPhase, SwappingTheShapesFlipsTheNormalAndKeepsThePoints)
{
    const double h = 0.5;
    const CollisionShape slab = box({4, 1, 4}), cube = box({1, 1, 1}), ball = CollisionShape::of(Shape::sphere(0.25));
    const CollisionShape cylinder = CollisionShape::of(Shape::cylinder(0.5, 1.0));
    struct Pair {
        const CollisionShape &a, &b;
        Transform ta, tb;
    };
    const Pair pairs[] = {
        {slab, cube, pose({0, 0, 0}), pose({0.2, 1.0, -0.1})},
        {slab, cube, pose({0, 0, 0}),
         pose({0.1, 0.5 + h * (1 + 1 / kSqrt2) - 0.01, 0.2}, rotation(45, {0, 0, 1}) * rotation(45, {1, 0, 0}))},
        {cube, cube, pose({0, 0, 0}, rotation(45, {0, 0, 1})), pose({0.05, 2 * h * kSqrt2 - 0.02, 0.1}, rotation(45, {1, 0, 0}))},
        {slab, ball, pose({0, 0, 0}), pose({2.1, 0.6, 0.3})},
        {slab, cylinder, pose({0, 0, 0}), pose({0.3, 0.99, -0.2})},
    };
    for (const Pair& p : pairs) {
        const Manifold ab = collide(p.a, p.ta, p.b, p.tb, 0.01), ba = collide(p.b, p.tb, p.a, p.ta, 0.01);
        EXPECT_GT(ab.count, 0);
        expectSwapped(ab, ba);
    }
}

bool finite(const Manifold& m)
{
    bool ok = std::isfinite(m.normal.x) && std::isfinite(m.normal.y) && std::isfinite(m.normal.z);
    for (int k = 0; k < m.count; ++k) {
        const ManifoldPoint& p = m.points[static_cast<std::size_t>(k)];
        for (const dvec3& v : {p.anchorA, p.anchorB, p.point})
            ok = ok && std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
        ok = ok && std::isfinite(p.separation);
    }
    return ok;
}

// Coincident centres have no direction between them: the manifold still has a unit normal (for
// two spheres, +y; they are rA + rB deep), finite points, and no NaN.
TEST(NarrowPhase, CoincidentShapesGiveAFiniteNormal)
{
    const CollisionShape ball = CollisionShape::of(Shape::sphere(0.3)), cube = box({1, 1, 1});
    const CollisionShape cylinder = CollisionShape::of(Shape::cylinder(0.5, 1.0));
    const Transform at = pose({1, 2, 3}, rotation(20, {1, 2, 3}));
    const Manifold spheres = collide(ball, at, ball, at, 0.0);
    ASSERT_EQ(spheres.count, 1);
    EXPECT_EQ(spheres.normal, dvec3(0, 1, 0));
    EXPECT_DOUBLE_EQ(spheres.points[0].separation, -0.6);
    for (const auto& [a, b] : {std::pair{&cube, &cube}, std::pair{&cube, &ball}, std::pair{&ball, &cube},
                               std::pair{&cylinder, &cylinder}, std::pair{&cylinder, &cube}}) {
        const Manifold m = collide(*a, at, *b, at, 0.0);
        EXPECT_GT(m.count, 0);
        EXPECT_TRUE(finite(m));
        EXPECT_NEAR(glm::length(m.normal), 1.0, 1e-12);
    }
    // Two cubes exactly face to face share parallel edges everywhere: still a face manifold.
    const Manifold stacked = collide(cube, pose({0, 0, 0}), cube, pose({0, 1, 0}), 0.0);
    EXPECT_EQ(stacked.count, 4);
    EXPECT_TRUE(finite(stacked));
}

// A box of zero height and a prism of zero height have faces of zero area and edges of zero
// length (their sides): no side plane, edge axis or closest point divides by them. Lying on a
// box's top, the flat box touches at its four corners at the depth asked, normal up; against a
// sphere and each other the manifolds are finite.
TEST(NarrowPhase, ZeroAreaFacesGiveNoNaN)
{
    const auto flat = [](const ConvexPolyhedron& p) {
        return CollisionShape{CollisionShape::Kind::Polyhedron, 0.0, std::make_shared<const ConvexPolyhedron>(p)};
    };
    const CollisionShape sheet = flat(ConvexPolyhedron::box({0.5, 0.0, 0.5})), disc = flat(ConvexPolyhedron::prism(0.5, 0.0, 24));
    const CollisionShape slab = box({4, 1, 4}), ball = CollisionShape::of(Shape::sphere(0.25));
    const Manifold lying = collide(slab, pose({0, 0, 0}), sheet, pose({0.1, 0.499, 0}), 0.0);
    ASSERT_EQ(lying.count, 4);
    expectNear(lying.normal, {0, 1, 0}, 1e-15);
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(lying.points[static_cast<std::size_t>(k)].separation, -0.001, 1e-12);
    const dmat3 tilted = rotation(30, {1, 0, 1});
    for (const auto& [a, b] : {std::pair{&sheet, &slab}, std::pair{&sheet, &ball}, std::pair{&ball, &disc},
                               std::pair{&disc, &slab}, std::pair{&disc, &sheet}, std::pair{&sheet, &sheet}}) {
        for (const dvec3& at : {dvec3(0.0), dvec3(0.1, 0.2, 0.0), dvec3(0.3, 0.0, 0.1)}) {
            const Manifold m = collide(*a, pose({0, 0, 0}, tilted), *b, pose(at), 0.01);
            EXPECT_TRUE(finite(m));
            EXPECT_NEAR(glm::length(m.normal), 1.0, 1e-12);
        }
    }
}

// The SAT cache only lets a pair skip the full test when its last axis still separates it by
// more than the margin, where the full test finds no contact either: a box passing over and
// through another, turning, gets bit-identical manifolds with and without a cache.
TEST(NarrowPhase, CacheLeavesEveryManifoldAsItWas)
{
    const CollisionShape a = box({1, 0.6, 0.8}), b = box({0.5, 0.7, 0.4});
    const Transform ta = pose({0, 0, 0}, rotation(10, {0, 1, 0}));
    SatCache cache;
    int touching = 0;
    for (int step = 0; step < 400; ++step) {
        const double t = step / 400.0;
        const Transform tb = pose({-2.0 + 4.0 * t, 1.2 - 1.4 * t, 0.1 * std::sin(9 * t)}, rotation(700 * t, {1, 2, 0.5}));
        const Manifold plain = collide(a, ta, b, tb, 0.02), cached = collide(a, ta, b, tb, 0.02, &cache);
        ASSERT_EQ(plain.count, cached.count) << "step " << step;
        touching += plain.count > 0;
        EXPECT_EQ(plain.normal, cached.normal);
        for (int k = 0; k < plain.count; ++k) {
            const ManifoldPoint &p = plain.points[static_cast<std::size_t>(k)], &q = cached.points[static_cast<std::size_t>(k)];
            EXPECT_EQ(p.id, q.id);
            EXPECT_EQ(p.separation, q.separation);
            EXPECT_EQ(p.point, q.point);
        }
    }
    EXPECT_GT(touching, 50);
    EXPECT_LT(touching, 350);
}

// Up and to the +x side of a box, the other is beyond both its +x face (0) and its +y face (2);
// the full test stops at the first, face 0. A cache holding face 2 is still separating, so the
// full test is skipped and the cache stays at face 2. A cache whose indices no longer fit the
// shapes is ignored.
TEST(NarrowPhase, CacheSkipsTheFullTestWhileItsAxisSeparates)
{
    const CollisionShape cube = box({1, 1, 1});
    const Transform ta = pose({0, 0, 0}), tb = pose({1.5, 1.5, 0});
    SatCache fresh;
    EXPECT_EQ(collide(cube, ta, cube, tb, 0.01, &fresh).count, 0);
    EXPECT_EQ(fresh.axis, SatCache::Axis::FaceA);
    EXPECT_EQ(fresh.indexA, 0u);
    SatCache kept{SatCache::Axis::FaceA, 2, 0};
    EXPECT_EQ(collide(cube, ta, cube, tb, 0.01, &kept).count, 0);
    EXPECT_EQ(kept.axis, SatCache::Axis::FaceA);
    EXPECT_EQ(kept.indexA, 2u);
    SatCache stale{SatCache::Axis::Edges, 500, 7};
    EXPECT_EQ(collide(cube, ta, cube, tb, 0.01, &stale).count, 0);
    EXPECT_EQ(stale.axis, SatCache::Axis::FaceA);
    // Resting, the cache holds the reference face: the slab's top (+y, face 2).
    SatCache resting;
    EXPECT_EQ(collide(box({2, 1, 2}), ta, cube, pose({0, 1, 0}), 0.01, &resting).count, 4);
    EXPECT_EQ(resting.axis, SatCache::Axis::FaceA);
    EXPECT_EQ(resting.indexA, 2u);
}

// --- Random box pairs against an independent measurement ---------------------------------

struct Box {
    dvec3 half;
    Transform pose;
};

/// The parameters where the line p + t n enters and leaves the box (slab method, in the box's
/// frame), its faces pushed out by 1e-11 so that a line running along a face still meets it.
std::pair<double, double> lineThroughBox(const Box& box, const dvec3& p, const dvec3& n)
{
    const dvec3 o = box.pose.applyInverse(p), d = glm::transpose(box.pose.rotation) * n;
    double enter = -INFINITY, leave = INFINITY;
    for (int i = 0; i < 3; ++i) {
        const double h = box.half[i] + 1e-11;
        if (std::abs(d[i]) < 1e-300) {
            if (std::abs(o[i]) > h)
                return {INFINITY, -INFINITY};
            continue;
        }
        const double t0 = (-h - o[i]) / d[i], t1 = (h - o[i]) / d[i];
        enter = std::max(enter, std::min(t0, t1));
        leave = std::min(leave, std::max(t0, t1));
    }
    return {enter, leave};
}

/// The largest gap between the boxes' projections over the 15 axes of two boxes (their 3 + 3
/// face normals and 9 cross products of edges), from all 16 corners.
double satDistance(const Box& a, const Box& b)
{
    std::vector<dvec3> axes;
    for (int i = 0; i < 3; ++i) {
        axes.push_back(a.pose.rotation[i]);
        axes.push_back(b.pose.rotation[i]);
        for (int j = 0; j < 3; ++j)
            if (const dvec3 c = glm::cross(a.pose.rotation[i], b.pose.rotation[j]); glm::length(c) > 1e-9)
                axes.push_back(glm::normalize(c));
    }
    double best = -INFINITY;
    for (const dvec3& u : axes) {
        double loA = INFINITY, hiA = -INFINITY, loB = INFINITY, hiB = -INFINITY;
        for (int c = 0; c < 8; ++c) {
            const dvec3 s(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
            const double pa = glm::dot(u, a.pose.apply(s * a.half)), pb = glm::dot(u, b.pose.apply(s * b.half));
            loA = std::min(loA, pa), hiA = std::max(hiA, pa), loB = std::min(loB, pb), hiB = std::max(hiB, pb);
        }
        best = std::max(best, std::max(loB - hiA, loA - hiB));
    }
    return best;
}

/// A box as its hull: the same solid, but not marked a box, so the narrow phase takes it through
/// the general search (faces, and edge pairs pruned on the Gauss map) instead of the closed form.
CollisionShape boxAsHull(const dvec3& half)
{
    std::vector<dvec3> corners;
    for (int c = 0; c < 8; ++c)
        corners.push_back(half * dvec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1));
    CollisionShape shape;
    shape.kind = CollisionShape::Kind::Polyhedron;
    shape.polyhedron = std::make_shared<const ConvexPolyhedron>(ConvexPolyhedron::hull(corners));
    return shape;
}

/// Random box pairs (sides 0.2 to 1 m, turned at random) brought together along a random
/// direction until they overlap by 2 mm (bisection on the brute-force separating-axis distance,
/// which only grows as the centres part).
std::vector<std::pair<Box, Box>> overlappingBoxPairs(int count)
{
    std::mt19937_64 rng(62);
    std::uniform_real_distribution<double> side(0.2, 1.0);
    std::normal_distribution<double> gauss;
    const auto randomRotation = [&] {
        return glm::mat3_cast(glm::normalize(pba::dquat(gauss(rng), gauss(rng), gauss(rng), gauss(rng))));
    };
    std::vector<std::pair<Box, Box>> pairs;
    for (int trial = 0; trial < count; ++trial) {
        Box a{0.5 * dvec3(side(rng), side(rng), side(rng)), pose({0, 0, 0}, randomRotation())};
        Box b{0.5 * dvec3(side(rng), side(rng), side(rng)), pose({0, 0, 0}, randomRotation())};
        const dvec3 direction = glm::normalize(dvec3(gauss(rng), gauss(rng), gauss(rng)));
        double lo = 0.0, hi = 4.0;
        for (int i = 0; i < 80; ++i) {
            const double mid = 0.5 * (lo + hi);
            b.pose.position = mid * direction;
            (satDistance(a, b) < -0.002 ? lo : hi) = mid;
        }
        b.pose.position = lo * direction;
        pairs.emplace_back(a, b);
    }
    return pairs;
}

// For random slightly overlapping box pairs, each point's separation must be where the line
// through it along the normal enters B less where it leaves A (the line leaves A's reference
// face or edge at the point's A side and enters B's at its B side), within 1e-9; its anchors
// must lie on the boxes' surfaces; and the normal must separate the boxes within the preference
// slack of the best of the 15 axes. Both as boxes (the closed form) and as hulls (the general
// search over faces and Gauss-map edge pairs).
TEST(NarrowPhase, RandomBoxPairsAgreeWithTheSlabMethod)
{
    int points = 0, edgeContacts = 0;
    const auto pairs = overlappingBoxPairs(300);
    for (std::size_t trial = 0; trial < pairs.size(); ++trial) {
        const auto& [a, b] = pairs[trial];
        for (const bool hulls : {false, true}) {
            const Manifold m = hulls ? collide(boxAsHull(a.half), a.pose, boxAsHull(b.half), b.pose, 0.0)
                                     : collide(box(2.0 * a.half), a.pose, box(2.0 * b.half), b.pose, 0.0);
            ASSERT_GT(m.count, 0) << "trial " << trial;
            ASSERT_TRUE(finite(m));
            expectConsistent(m, a.pose, b.pose);
            // The gap along the normal, as satDistance measures it.
            double loA = INFINITY, hiA = -INFINITY, loB = INFINITY, hiB = -INFINITY;
            for (int c = 0; c < 8; ++c) {
                const dvec3 s(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
                const double pa = glm::dot(m.normal, a.pose.apply(s * a.half)), pb = glm::dot(m.normal, b.pose.apply(s * b.half));
                loA = std::min(loA, pa), hiA = std::max(hiA, pa), loB = std::min(loB, pb), hiB = std::max(hiB, pb);
            }
            const double slack = 2e-3 * std::min(glm::length(a.half), glm::length(b.half));
            EXPECT_GE(loB - hiA, satDistance(a, b) - slack - 1e-9) << "trial " << trial;
            edgeContacts += kindA(m.points[0].id) == static_cast<std::uint32_t>(Feature::Edge) &&
                            kindB(m.points[0].id) == static_cast<std::uint32_t>(Feature::Edge);
            for (int k = 0; k < m.count; ++k) {
                const ManifoldPoint& p = m.points[static_cast<std::size_t>(k)];
                const auto [enterA, leaveA] = lineThroughBox(a, p.point, m.normal);
                const auto [enterB, leaveB] = lineThroughBox(b, p.point, m.normal);
                ASSERT_LE(enterA, leaveA) << "trial " << trial << " point " << k;
                ASSERT_LE(enterB, leaveB) << "trial " << trial << " point " << k;
                EXPECT_NEAR(p.separation, enterB - leaveA, 1e-9) << "trial " << trial << " point " << k;
                for (const auto& [anchor, half] : {std::pair{p.anchorA, a.half}, std::pair{p.anchorB, b.half}}) {
                    const dvec3 q = glm::abs(anchor) - half;
                    EXPECT_NEAR(std::max({q.x, q.y, q.z}), 0.0, 1e-9) << "trial " << trial << " point " << k;
                }
                ++points;
            }
        }
    }
    EXPECT_GT(points, 600);
    EXPECT_GT(edgeContacts, 0);
}

// The closed form for two boxes finds what the general search finds for the same two solids:
// the same normal and the same points (the reduction to four keeps points by depth and area, so
// the faces' numbering does not matter), for random overlapping pairs.
TEST(NarrowPhase, BoxesInClosedFormMatchTheGeneralSearch)
{
    const auto pairs = overlappingBoxPairs(200);
    for (std::size_t trial = 0; trial < pairs.size(); ++trial) {
        const auto& [a, b] = pairs[trial];
        const Manifold closed = collide(box(2.0 * a.half), a.pose, box(2.0 * b.half), b.pose, 0.01);
        const Manifold general = collide(boxAsHull(a.half), a.pose, boxAsHull(b.half), b.pose, 0.01);
        ASSERT_EQ(closed.count, general.count) << "trial " << trial;
        expectNear(closed.normal, general.normal, 1e-9);
        for (int k = 0; k < closed.count; ++k) {
            const ManifoldPoint& p = closed.points[static_cast<std::size_t>(k)];
            const bool found = std::any_of(general.points.begin(), general.points.begin() + general.count,
                                           [&](const ManifoldPoint& q) {
                                               return glm::length(q.point - p.point) < 1e-9 &&
                                                      std::abs(q.separation - p.separation) < 1e-9;
                                           });
            EXPECT_TRUE(found) << "trial " << trial << " point " << k;
        }
    }
}

/// How far `x` (in the shape's frame) lies outside its surface: the largest height above a
/// face's plane for a polyhedron (0 on the surface), |x| - r for a sphere.
double surfaceHeight(const CollisionShape& shape, const dvec3& x)
{
    if (shape.kind == CollisionShape::Kind::Sphere)
        return glm::length(x) - shape.radius;
    double height = -INFINITY;
    for (const ConvexPolyhedron::Face& f : shape.polyhedron->faces)
        height = std::max(height, glm::dot(f.normal, x) - f.offset);
    return height;
}

// Every kind of pair (spheres, boxes, the cylinder's prism, a 60-sided prism whose caps clip on
// the heap, hulls of random points) at random poses near each other, some coincident: the
// manifold has a unit normal, at most four points, none beyond the margin, each anchor on its
// shape's surface and each point consistent with its anchors, and nothing is NaN.
TEST(NarrowPhase, EveryPairOfShapesGivesAConsistentManifold)
{
    std::mt19937_64 rng(2013);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<dvec3> cloud;
    for (int i = 0; i < 40; ++i)
        cloud.push_back(0.4 * dvec3(gauss(rng), gauss(rng), gauss(rng)));
    CollisionShape fine;
    fine.kind = CollisionShape::Kind::Polyhedron;
    fine.polyhedron = std::make_shared<const ConvexPolyhedron>(ConvexPolyhedron::prism(0.4, 0.5, 60));
    const std::vector<CollisionShape> shapes{
        CollisionShape::of(Shape::sphere(0.3)), box({0.6, 0.4, 0.8}), CollisionShape::of(Shape::cylinder(0.35, 0.7)),
        fine, CollisionShape{CollisionShape::Kind::Polyhedron, 0.0, std::make_shared<const ConvexPolyhedron>(ConvexPolyhedron::hull(cloud))}};
    const auto randomRotation = [&] {
        return glm::mat3_cast(glm::normalize(pba::dquat(gauss(rng), gauss(rng), gauss(rng), gauss(rng))));
    };
    const double margin = 0.02;
    int touching = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const CollisionShape &a = shapes[static_cast<std::size_t>(trial) % shapes.size()],
                             &b = shapes[static_cast<std::size_t>(trial / 5) % shapes.size()];
        const Transform ta = pose({0, 0, 0}, randomRotation());
        const double reach = (a.boundingRadius() + b.boundingRadius()) * unit(rng);
        const Transform tb = pose(trial % 17 == 0 ? dvec3(0.0) : reach * glm::normalize(dvec3(gauss(rng), gauss(rng), gauss(rng))),
                                  trial % 17 == 0 ? ta.rotation : randomRotation());
        const Manifold m = collide(a, ta, b, tb, margin);
        ASSERT_TRUE(finite(m)) << "trial " << trial;
        ASSERT_LE(m.count, Manifold::kMaxPoints);
        touching += m.count > 0;
        expectConsistent(m, ta, tb);
        for (int k = 0; k < m.count; ++k) {
            const ManifoldPoint& p = m.points[static_cast<std::size_t>(k)];
            EXPECT_LE(p.separation, margin);
            EXPECT_NEAR(surfaceHeight(a, p.anchorA), 0.0, 1e-9) << "trial " << trial << " point " << k;
            EXPECT_NEAR(surfaceHeight(b, p.anchorB), 0.0, 1e-9) << "trial " << trial << " point " << k;
        }
    }
    EXPECT_GT(touching, 200);
}

} // namespace

// What the scene loader asks before the first step: how deep one body starts in another.
TEST(NarrowPhase, OverlapDepthIsTheDeepestPointsDepth)
{
    pba::RigidBody table, box, ball;
    table.setShapeWithMass(Shape::box(dvec3(1.0, 0.1, 1.0)), 10.0);
    table.setPos(dvec3(0.0, 1.0, 0.0));
    box.setShapeWithMass(Shape::box(dvec3(0.1)), 1.0);
    box.setPos(dvec3(0.2, 1.07, 0.0)); // its bottom 3 cm below the table's top
    EXPECT_NEAR(pba::overlapDepth(table, box), 0.03, 1e-12);
    box.setPos(dvec3(0.2, 1.1, 0.0)); // resting on it
    EXPECT_NEAR(pba::overlapDepth(table, box), 0.0, 1e-12);
    ball.setShapeWithMass(Shape::sphere(0.1), 1.0);
    ball.setPos(dvec3(3.0, 1.0, 0.0)); // far away
    EXPECT_EQ(pba::overlapDepth(table, ball), 0.0);
}
