// A rope's and a cloth's pieces against rigid bodies: how thick a piece is and where a point lies
// on it, where a segment or a triangle of balls lies deepest in a shape, against cases worked by
// hand (each beside its test), and what it does in a world: a rope dropped across a bar thinner
// than the gap between its balls hangs over the bar instead of falling through it between two
// balls.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "core/balls/piece_geometry.hpp"
#include "core/rigid/piece_contacts.hpp"
#include "pba/scene/scene.hpp"
#include "pba/shape.hpp"

namespace {

using pba::dvec3;
using pba::contact::CollisionShape;
using pba::contact::Transform;
using pba::rigid::deepestBetweenBalls;
using pba::rigid::SegmentDepths;

constexpr double kMargin = 0.01; // the contact margin's default

const CollisionShape& unitCube()
{
    static const CollisionShape cube = CollisionShape::of(pba::Shape::box(dvec3(1.0)));
    return cube;
}

const Transform kAtOrigin{dvec3(0.0), pba::dmat3(1.0)};

} // namespace

// Balls of radii 0.1 and 0.2, 1 m apart, leave a gap of 0.7: the segment is at most 0.35 thick.
// A triangle (0,0,0), (1,0,0), (0,1,0) of radii 0.1 has gaps 0.8, 0.8 and sqrt 2 - 0.2: 0.4.
// Touching balls leave no piece.
TEST(PieceGeometry, APieceIsNoThickerThanHalfItsSmallestGap)
{
    using pba::detail::thickestPiece;
    EXPECT_DOUBLE_EQ(thickestPiece(std::array{dvec3(0.0), dvec3(1.0, 0.0, 0.0)}, std::array{0.1, 0.2}), 0.35);
    EXPECT_DOUBLE_EQ(thickestPiece(std::array{dvec3(0.0), dvec3(1.0, 0.0, 0.0), dvec3(0.0, 1.0, 0.0)},
                                   std::array{0.1, 0.1, 0.1}),
                     0.4);
    EXPECT_EQ(thickestPiece(std::array{dvec3(0.0), dvec3(0.2, 0.0, 0.0)}, std::array{0.1, 0.1}), 0.0);
}

// (0.25, 3, 0) has its foot at a quarter of the segment from (0,0,0) to (1,0,0): weights 3/4,
// 1/4; (0.2, 0.3, 5) on the triangle above lies at 1/2, 1/5, 3/10. A foot within half a percent
// of an end or a side, or outside, is that ball's or side's own contact.
TEST(PieceGeometry, APointsFootLiesOnAPieceByWeightsOnItsBalls)
{
    using pba::detail::footOnPiece;
    std::array<double, 3> w{};
    ASSERT_TRUE(footOnPiece(dvec3(0.25, 3.0, 0.0), std::array{dvec3(0.0), dvec3(1.0, 0.0, 0.0)}, w));
    EXPECT_DOUBLE_EQ(w[0], 0.75);
    EXPECT_DOUBLE_EQ(w[1], 0.25);
    EXPECT_EQ(w[2], 0.0);
    const std::array triangle{dvec3(0.0), dvec3(1.0, 0.0, 0.0), dvec3(0.0, 1.0, 0.0)};
    ASSERT_TRUE(footOnPiece(dvec3(0.2, 0.3, 5.0), triangle, w));
    EXPECT_NEAR(w[0], 0.5, 1e-15);
    EXPECT_NEAR(w[1], 0.2, 1e-15);
    EXPECT_NEAR(w[2], 0.3, 1e-15);
    EXPECT_FALSE(footOnPiece(dvec3(0.002, 0.0, 1.0), std::array{dvec3(0.0), dvec3(1.0, 0.0, 0.0)}, w));
    EXPECT_FALSE(footOnPiece(dvec3(0.5, 0.002, 0.0), triangle, w));
    EXPECT_FALSE(footOnPiece(dvec3(0.8, 0.8, 0.0), triangle, w));
    EXPECT_FALSE(footOnPiece(dvec3(0.5, 0.5, 0.0), std::array{dvec3(0.0), dvec3(1.0, 0.0, 0.0), dvec3(2.0, 0.0, 0.0)}, w));
}

// The segment from (0.6, 0.45, 0) to (0.45, 0.6, 0), radius 0.05 (its balls 0.21 m apart, far
// from touching), passes over the cube's edge x = y = 0.5: its point (0.6 - 0.15 t, 0.45 + 0.15 t)
// is sqrt((0.1 - 0.15 t)^2 + (0.15 t - 0.05)^2) from the edge, least at t = 1/2, 0.025 sqrt(2).
// There it overlaps by 0.05 - 0.0354 = 0.0146 along (1, 1, 0)/sqrt(2); its balls are each 0.1 from
// a face, separated by 0.05.
TEST(PieceContact, ASegmentAcrossABoxEdgeTouchesItAtTheEdgeAlongTheBisector)
{
    const SegmentDepths d =
        deepestBetweenBalls(unitCube(), kAtOrigin, {0.6, 0.45, 0.0}, 0.05, {0.45, 0.6, 0.0}, 0.05, kMargin);
    ASSERT_EQ(d.count, 1);
    const auto& p = d.points[0];
    // (The search finds t to 1/4000 of the segment.)
    EXPECT_NEAR(p.t, 0.5, 2.5e-4);
    EXPECT_NEAR(p.separation, 0.025 * std::numbers::sqrt2 - 0.05, 1e-6);
    EXPECT_NEAR(p.line, 0.05, 1e-12);
    EXPECT_NEAR(p.normal.x, 1.0 / std::numbers::sqrt2, 2e-3);
    EXPECT_NEAR(p.normal.y, 1.0 / std::numbers::sqrt2, 2e-3);
    EXPECT_NEAR(p.normal.z, 0.0, 1e-12);
    EXPECT_NEAR(p.point.x, 0.525, 1e-4);
    EXPECT_NEAR(p.point.y, 0.525, 1e-4);
}

// A steep segment from (0.5, 0.62, 0), its ball 7 cm above the cube's top, to (0.6, -0.8, 0), its
// ball hanging below the bottom edge, radius 0.05: it passes the top edge x = y = 0.5 at
// 0.12 * 0.1 / |(0.1, -1.42)| = 8.43 mm, nearest at t = 0.12 * 1.42 / 2.0264 = 0.0841, so it
// overlaps there by 41.57 mm along its own normal (1.42, 0.1) / |.|. (Its balls' line, 0.07 to
// 0.2662, rises faster along it than the right face's distance does, so the point deepest beyond
// that line lies low on the right face, clear of it.)
TEST(PieceContact, ASteepSegmentPastAnEdgeTouchesItWhereItComesNearest)
{
    const SegmentDepths d =
        deepestBetweenBalls(unitCube(), kAtOrigin, {0.5, 0.62, 0.0}, 0.05, {0.6, -0.8, 0.0}, 0.05, kMargin);
    ASSERT_EQ(d.count, 1);
    const auto& p = d.points[0];
    const double length = std::sqrt(0.1 * 0.1 + 1.42 * 1.42);
    EXPECT_NEAR(p.t, 0.12 * 1.42 / (length * length), 2.5e-4);
    EXPECT_NEAR(p.separation, 0.012 / length - 0.05, 1e-6);
    // The normal points from the edge to the point found, a four-thousandth of the segment (0.36
    // mm) from the nearest at most, 8.43 mm from the edge: within 0.042 rad of the true one.
    const double turn = 2.5e-4 * length / (0.012 / length);
    EXPECT_NEAR(p.normal.x, 1.42 / length, 1e-3);
    EXPECT_NEAR(p.normal.y, 0.1 / length, turn);
}

// A segment from (-0.6, 0.52, 0) to (0.6, 0.52, 0), radius 0.03, lies across the cube's top, 2 cm
// above it (overlapping by 1 cm) from x = -0.5 to 0.5, its balls beyond the two edges: as deep all
// along that stretch, it touches at the stretch's two ends, t = 0.1/1.2 and 1.1/1.2, both along +y.
TEST(PieceContact, ASegmentLyingAcrossAFaceTouchesItAtBothEndsOfTheStretch)
{
    const SegmentDepths d =
        deepestBetweenBalls(unitCube(), kAtOrigin, {-0.6, 0.52, 0.0}, 0.03, {0.6, 0.52, 0.0}, 0.03, kMargin);
    ASSERT_EQ(d.count, 2);
    // The stretch reaches as far as the separation stays within 10 um of its least: beyond an
    // edge, to where sqrt(0.02^2 + dx^2) = 0.02001, dx = 0.63 mm (5.3e-4 of the segment), found
    // to 1/4096 of the way from the segment's end.
    EXPECT_NEAR(d.points[0].t, 0.1 / 1.2, 6.5e-4);
    EXPECT_NEAR(d.points[1].t, 1.1 / 1.2, 6.5e-4);
    for (const auto& p : d.points) {
        EXPECT_NEAR(p.separation, -0.01, 1e-5);
        EXPECT_GT(p.normal.y, 0.999);
    }
}

// The same segment 3 cm above the top, as its balls would rest on it, is level with them: the
// balls' own contacts hold it, and it adds none.
TEST(PieceContact, ASegmentAlongAFaceAsItsBallsRestAddsNoContact)
{
    EXPECT_EQ(deepestBetweenBalls(unitCube(), kAtOrigin, {-0.3, 0.53, 0.0}, 0.03, {0.3, 0.53, 0.0}, 0.03, kMargin)
                  .count,
              0);
}

// Balls that touch (0.06 apart, radius 0.03) cover their segment: a body in the groove between
// them rests on them.
TEST(PieceContact, TouchingBallsHaveNoSegment)
{
    EXPECT_EQ(deepestBetweenBalls(unitCube(), kAtOrigin, {-0.03, 0.51, 0.0}, 0.03, {0.03, 0.51, 0.0}, 0.03, kMargin)
                  .count,
              0);
}

// Across the top of a sphere of radius 1 at the origin, 1.01 up, radius 0.02: deepest above the
// centre (t = 1/2), overlapping by 0.01 along +y; its balls sqrt(2.0201) - 1.02 from the sphere.
TEST(PieceContact, ASegmentOverASphereTouchesItAboveItsCentre)
{
    const CollisionShape sphere = CollisionShape::of(pba::Shape::sphere(1.0));
    const SegmentDepths d =
        deepestBetweenBalls(sphere, kAtOrigin, {-1.0, 1.01, 0.0}, 0.02, {1.0, 1.01, 0.0}, 0.02, kMargin);
    ASSERT_EQ(d.count, 1);
    EXPECT_NEAR(d.points[0].t, 0.5, 2.5e-4);
    EXPECT_NEAR(d.points[0].separation, -0.01, 1e-6);
    EXPECT_NEAR(d.points[0].line, std::sqrt(2.0201) - 1.02, 1e-12);
    EXPECT_NEAR(d.points[0].normal.y, 1.0, 1e-6);
}

// A cloth's triangle of 3 cm balls at (0.1, 0.49, 0.8), (0.8, 0.49, 0.8) and (0.8, 0.49, 0.1), level
// 1 cm below the cube's top, its balls beside it: the cube's corner (0.5, 0.5, 0.5) comes up
// through its inside, its foot at weights (3/7, 1/7, 3/7) (from (0.4, -0.3) = u (0.7, 0) +
// v (0.7, -0.7) in x and z), 1 cm above the triangle's middle plane: 4 cm into it, along +y. Its
// balls are 0.27, 0.394 and 0.27 from the cube.
TEST(PieceContact, ABoxCornerThroughACellsTriangleTouchesItThere)
{
    const std::array<dvec3, 3> x{dvec3(0.1, 0.49, 0.8), dvec3(0.8, 0.49, 0.8), dvec3(0.8, 0.49, 0.1)};
    const auto d = pba::rigid::deepestUnderTriangle(unitCube(), kAtOrigin, x, {0.03, 0.03, 0.03}, kMargin);
    ASSERT_TRUE(d.has_value());
    EXPECT_NEAR(d->weights[0], 3.0 / 7.0, 1e-12);
    EXPECT_NEAR(d->weights[1], 1.0 / 7.0, 1e-12);
    EXPECT_NEAR(d->weights[2], 3.0 / 7.0, 1e-12);
    EXPECT_NEAR(d->separation, -0.04, 1e-12);
    EXPECT_NEAR(glm::length(d->normal - dvec3(0, 1, 0)), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(d->point - dvec3(0.5, 0.5, 0.5)), 0.0, 1e-12);
    const double corner = std::sqrt(0.18) - 0.03; // the middle ball from the cube's edge
    EXPECT_NEAR(d->line, 3.0 / 7.0 * 0.27 + 1.0 / 7.0 * corner + 3.0 / 7.0 * 0.27, 1e-9);
}

// The same triangle 3 cm above the top, its balls' separations level with its own (as they would
// rest on a face): no contact of its own.
TEST(PieceContact, ATriangleLyingOnAFaceAsItsBallsRestAddsNoContact)
{
    const std::array<dvec3, 3> x{dvec3(-0.3, 0.53, 0.3), dvec3(0.3, 0.53, 0.3), dvec3(0.3, 0.53, -0.3)};
    EXPECT_FALSE(pba::rigid::deepestUnderTriangle(unitCube(), kAtOrigin, x, {0.03, 0.03, 0.03}, kMargin).has_value());
}

// A rope of ten 2 cm balls 20 cm apart dropped across a fixed bar 2 cm thick, which lies between
// its two middle balls: without its segments it fell between them to the floor; it hangs over the
// bar, and no point between two balls comes within a ball's radius of the bar (less a
// millimetre), measured here from the bar's faces. Neither bouncing, and with the particles'
// default restitution of 1 (the rope then whips over the bar, its links steep, and its two ends
// swing into each other under it at 6 m/s and rebound, so they need not end on their own sides).
class RopeOverABar : public ::testing::TestWithParam<const char*> {};

TEST_P(RopeOverABar, ARopeDroppedAcrossAThinBarHangsOverIt)
{
    const std::string restitution = GetParam();
    pba::Scene scene = pba::parseScene(
        R"({"dt": 0.002, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
            "ropes": [{"name": "rope", "from": [-0.9, 1.2, 0], "to": [0.9, 1.2, 0], "count": 10, "mass": 0.2,
                       "stiffness": 500, "damping": 0.5, "radius": 0.02, "friction": 0.5)" + restitution + R"(}],
            "rigid_bodies": [{"name": "bar", "shape": {"type": "box", "size": [0.02, 0.02, 1]}, "density": 500,
                              "position": [0, 1, 0], "fixed": true, "friction": 0.5)" + restitution + R"(}]})",
        "rope-over-a-bar.json");
    pba::World& world = scene.world;
    // The bar's half sizes: x and y 0.01 about (0, 1), z 0.5.
    const auto distanceToBar = [](const dvec3& p) {
        const dvec3 outside = glm::max(glm::abs(p - dvec3(0.0, 1.0, 0.0)) - dvec3(0.01, 0.01, 0.5), dvec3(0.0));
        return glm::length(outside);
    };
    double nearest = INFINITY;
    for (int step = 0; step < 2500; ++step) {
        world.step(scene.dt);
        for (std::size_t i = 0; i + 1 < 10; ++i) {
            const dvec3 a = world.body(i).getPos(), b = world.body(i + 1).getPos();
            for (int k = 0; k <= 50; ++k)
                nearest = std::min(nearest, distanceToBar(a + (b - a) * (k / 50.0)));
        }
    }
    EXPECT_GT(nearest, 0.02 - 0.001);
    // Over the bar: a ball above its top, its neighbours on either side.
    std::size_t top = 0;
    for (std::size_t i = 1; i < 10; ++i)
        if (world.body(i).getPos().y > world.body(top).getPos().y)
            top = i;
    ASSERT_TRUE(top > 0 && top < 9);
    EXPECT_GT(world.body(top).getPos().y, 1.01);
    EXPECT_LT(world.body(top - 1).getPos().x, -0.01);
    EXPECT_GT(world.body(top + 1).getPos().x, 0.01);
}

INSTANTIATE_TEST_SUITE_P(PieceContact, RopeOverABar, ::testing::Values(R"(, "restitution": 0)", ""),
                         [](const auto& param) { return param.index == 0 ? "NotBouncing" : "DefaultRestitution"; });
