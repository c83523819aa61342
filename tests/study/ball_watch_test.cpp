// BallWatch, what `pba sim` prints about particles with a radius, against cases whose answer is
// known by construction (fixed balls and a fixed box, which no contact moves) or measured here
// from the same states.
#include <cmath>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "pba/scene/scene.hpp"
#include "study/ball_watch.hpp"

namespace pba::study {
namespace {

BallFigures watched(Scene& scene, int steps)
{
    BallWatch watch(scene.world, std::vector<bool>(scene.world.bodyCount(), false));
    for (int n = 0; n < steps; ++n) {
        scene.world.step(scene.dt);
        watch.record(scene.world);
    }
    watch.finish(scene.world);
    return watch.figures();
}

// A fixed ball 5 cm into a fixed box: the watch reads the depth where it stands. Two fixed balls
// overlapping by 1 cm are no pair that collides (neither moves): none is reported.
TEST(BallWatch, ItReadsHowFarABallIsInABodyAndPassesOverFixedPairs)
{
    Scene scene = parseScene(R"({"dt": 0.01, "duration": 1, "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "particles": [
          {"name": "a", "position": [0, 1, 0], "radius": 0.1, "fixed": true},
          {"name": "b", "position": [0.29, 1, 0], "radius": 0.2, "fixed": true},
          {"name": "c", "position": [1.25, 1, 0], "radius": 0.1, "fixed": true}],
        "rigid_bodies": [{"name": "block", "shape": {"type": "box", "size": [0.6, 0.6, 0.6]}, "position": [1.6, 1, 0],
                          "fixed": true}]})",
                             "balls.json");
    const BallFigures f = watched(scene, 25);
    EXPECT_EQ(f.balls, 3u);
    EXPECT_EQ(f.deepestPair, 0.0);
    EXPECT_NEAR(f.deepestInBody, 0.05, 1e-12);
    EXPECT_EQ(f.deepestBody, "block");
    EXPECT_EQ(f.freeBalls, 0u) << "fixed balls are no group's";
}

// Thirty balls dropped into a narrow shaft heap up, the contacts' sweeps leaving some in each
// other: the deepest overlap the watch reads is the deepest of the states it looks at, every
// tenth step and the last, measured here from the centres.
TEST(BallWatch, AHeapsOverlapIsTheDeepestOfTheLooks)
{
    std::string particles;
    for (int i = 0; i < 30; ++i)
        particles += fmt::format(R"({}{{"name": "b{}", "position": [{}, {}, {}], "radius": 0.1, "restitution": 0.2,
                                    "friction": 0.5}})",
                                 i == 0 ? "" : ",", i, 0.15 * std::sin(2.4 * i), 0.3 + 0.25 * i, 0.15 * std::cos(2.4 * i));
    Scene scene = parseScene(R"({"dt": 0.005, "duration": 2, "room": {"min": [-0.35, 0, -0.35], "max": [0.35, 9, 0.35]},
        "particles": [)" + particles + "]}",
                             "shaft.json");
    World& world = scene.world;
    BallWatch watch(world, std::vector<bool>(world.bodyCount(), false));
    double deepest = 0.0;
    const int steps = 323; // not a whole number of looks: the last state is looked at too
    for (int n = 1; n <= steps; ++n) {
        world.step(scene.dt);
        watch.record(world);
        if (n % BallWatch::kEvery == 0 || n == steps)
            for (std::size_t i = 0; i < world.bodyCount(); ++i)
                for (std::size_t j = i + 1; j < world.bodyCount(); ++j)
                    deepest = std::max(deepest,
                                       (0.2 - glm::length(world.body(j).getPos() - world.body(i).getPos())) / 0.2);
    }
    watch.finish(world);
    EXPECT_GT(deepest, 0.01) << "the heap's balls are in each other at some look";
    EXPECT_DOUBLE_EQ(watch.figures().deepestPair, deepest);
}

// Three balls at rest in zero g, their surfaces 0.5 mm apart in a row, touch as one group from
// the start; a fourth 1 m away keeps them from being one. Balls of 1 cm 0.5 mm apart are
// not touching: the gap is more than a hundredth of their radii.
TEST(BallWatch, BallsTouchingInARowAreOneGroupFromTheStart)
{
    for (const bool fourth : {false, true}) {
        std::string particles = R"({"name": "a", "position": [0, 1, 0], "radius": 0.1},
            {"name": "b", "position": [0.2005, 1, 0], "radius": 0.1},
            {"name": "c", "position": [0.401, 1, 0], "radius": 0.1})";
        if (fourth)
            particles += R"(, {"name": "d", "position": [1.4, 1, 0], "radius": 0.1})";
        Scene scene = parseScene(R"({"dt": 0.01, "duration": 1, "gravity": [0, 0, 0],
            "room": {"min": [-2, 0, -2], "max": [2, 3, 2]}, "particles": [)" + particles + "]}",
                                 "row.json");
        const BallFigures f = watched(scene, 25);
        EXPECT_EQ(f.freeBalls, fourth ? 4u : 3u);
        EXPECT_EQ(f.deepestPair, 0.0);
        if (fourth) {
            EXPECT_FALSE(f.oneGroupFrom.has_value());
        } else {
            ASSERT_TRUE(f.oneGroupFrom.has_value());
            EXPECT_EQ(*f.oneGroupFrom, 0.0);
        }
    }
}

// What a scene puts in each other at the start is seen there, though the first step's contacts
// push it apart: two balls at rest in zero g, 2 cm into each other (a tenth of a diameter).
// (A scene may not start a ball inside a rigid body: the loader refuses it.)
TEST(BallWatch, WhatOverlapsAtTheStartIsSeenThere)
{
    Scene scene = parseScene(R"({"dt": 0.01, "duration": 1, "gravity": [0, 0, 0],
        "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "particles": [
          {"name": "a", "position": [0, 1, 0], "radius": 0.1},
          {"name": "b", "position": [0.18, 1, 0], "radius": 0.1}]})",
                             "start.json");
    const BallFigures f = watched(scene, 25);
    EXPECT_NEAR(f.deepestPair, 0.1, 1e-12);
    EXPECT_EQ(f.deepestPairAt, 0.0);
    EXPECT_GE(glm::length(scene.world.body(1).getPos() - scene.world.body(0).getPos()), 0.2 - 1e-9)
        << "the contacts pushed them apart";
}

// Balls at rest in zero g that no contact moves (no two touch, and the world has no springs), read
// as two nets by the edges the watch is given: a from (-0.3, 1, 0) to b at (0.3, 1, 0), radius 5
// cm, and c at (0, 1.09, 0) to d above it. c lies 0.09 from a-b's axis, 1 cm into it (5 + 5 cm);
// a free ball of 4 cm at (0.15, 0.93, 0), 0.07 from it, 2 cm in.
TEST(BallWatch, ItReadsHowFarABallGoesIntoAnotherNetsEdge)
{
    Scene scene = parseScene(R"({"dt": 0.01, "duration": 1, "gravity": [0, 0, 0],
        "room": {"min": [-2, 0, -2], "max": [2, 3, 2]}, "particles": [
          {"name": "a", "position": [-0.3, 1, 0], "radius": 0.05},
          {"name": "b", "position": [0.3, 1, 0], "radius": 0.05},
          {"name": "c", "position": [0, 1.09, 0], "radius": 0.05},
          {"name": "d", "position": [0, 2, 0], "radius": 0.05},
          {"name": "free", "position": [0.15, 0.93, 0], "radius": 0.04}]})",
                             "nets.json");
    std::vector<bool> inNet{true, true, true, true, false};
    BallWatch watch(scene.world, inNet, {{0, 1}, {2, 3}});
    for (int n = 0; n < BallWatch::kEvery; ++n) {
        scene.world.step(scene.dt);
        watch.record(scene.world);
    }
    const BallFigures f = watch.figures();
    EXPECT_EQ(f.nets, 2u);
    EXPECT_NEAR(f.deepestNetBallInEdge, 0.01, 1e-12);
    EXPECT_NEAR(f.deepestFreeInEdge, 0.02, 1e-12);
}

// The same with c and d at (0.1, 1.09, -0.3) and (0.1, 1.09, 0.3): the edge c-d crosses a-b 0.09
// above it, midway between c and d, 1 cm into it, where no ball is.
TEST(BallWatch, ItReadsHowFarTwoNetsEdgesCrossIntoEachOther)
{
    Scene scene = parseScene(R"({"dt": 0.01, "duration": 1, "gravity": [0, 0, 0],
        "room": {"min": [-2, 0, -2], "max": [2, 3, 2]}, "particles": [
          {"name": "a", "position": [-0.3, 1, 0], "radius": 0.05},
          {"name": "b", "position": [0.3, 1, 0], "radius": 0.05},
          {"name": "c", "position": [0.1, 1.09, -0.3], "radius": 0.05},
          {"name": "d", "position": [0.1, 1.09, 0.3], "radius": 0.05}]})",
                             "crossing.json");
    BallWatch watch(scene.world, std::vector<bool>(4, true), {{0, 1}, {2, 3}});
    for (int n = 0; n < BallWatch::kEvery; ++n) {
        scene.world.step(scene.dt);
        watch.record(scene.world);
    }
    EXPECT_NEAR(watch.figures().deepestNetBallInEdge, 0.01, 1e-12);
}

TEST(BallWatch, SmallBallsAMillimetreApartDoNotTouch)
{
    Scene scene = parseScene(R"({"dt": 0.01, "duration": 1, "gravity": [0, 0, 0],
        "room": {"min": [-2, 0, -2], "max": [2, 3, 2]}, "particles": [
          {"name": "a", "position": [0, 1, 0], "radius": 0.01},
          {"name": "b", "position": [0.0205, 1, 0], "radius": 0.01}]})",
                             "grains.json");
    EXPECT_FALSE(watched(scene, 25).oneGroupFrom.has_value());
}

} // namespace
} // namespace pba::study
