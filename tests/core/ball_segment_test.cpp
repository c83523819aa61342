// Balls against the pieces of ropes and cloths between their balls: segments (the springs between
// two balls) and a cloth's triangles. Oracles: a ball that hits a segment at its middle meets a
// body of the point's mass (each end carrying half of it: (1/(4m) + 1/(4m))^-1 = 2m for two balls
// of mass m), so an elastic ball of mass 2m stops and gives both ends its velocity, and with
// restitution e leaves at (1 - e)/2 of it, momentum and energy kept as two equal balls' head-on;
// at a triangle's centroid the point's mass is 3m (a third on each of three), so a ball of 3m
// stops and gives the triangle's three balls its velocity, the cell's fourth none; a ball dropped
// on a tightrope between two of its balls, or into a sparse sheet's cell, stays on it (without
// the pieces it fell through to the floor); two equal elastic links crossing at their middles
// meet as two points of mass 2m each, and so exchange their velocities; a rope dropped across a
// tightrope where neither has a ball hangs on it; the thread count changes nothing.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pba/scene/scene.hpp"

namespace {

using pba::dvec3;

/// A free link of two 0.1 kg balls of 2 cm radius 30 cm apart along x, and a 0.2 kg ball of 5 cm
/// radius coming down onto its middle at 1 m/s, all with restitution `e`, in no gravity.
pba::Scene ballOntoALink(const std::string& e)
{
    return pba::parseScene(R"({"dt": 0.001, "gravity": [0, 0, 0], "room": {"min": [-3, -3, -3], "max": [3, 3, 3]},
        "ropes": [{"name": "link", "from": [-0.15, 0, 0], "to": [0.15, 0, 0], "count": 2, "mass": 0.2,
                   "stiffness": 100, "radius": 0.02, "restitution": )" + e + R"(}],
        "particles": [{"name": "ball", "position": [0, 0.3, 0], "velocity": [0, -1, 0], "mass": 0.2,
                       "radius": 0.05, "restitution": )" + e + R"(}]})",
                           "ball-onto-a-link.json");
}

/// The world index of the body named `name`.
std::size_t named(const pba::World& world, const std::string& name)
{
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (world.body(i).getName() == name)
            return i;
    ADD_FAILURE() << "no body " << name;
    return 0;
}

/// Every body's state after `steps` steps of the scene `json` on `threads` threads.
std::vector<pba::State> statesAfter(const std::string& json, int steps, int threads)
{
    pba::Scene scene = pba::parseScene(json, "threads.json");
    scene.world.setThreads(threads);
    for (int step = 0; step < steps; ++step)
        scene.world.step(scene.dt);
    std::vector<pba::State> states;
    for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
        states.push_back(scene.world.body(i).getState());
    return states;
}

void expectSameStates(const std::vector<pba::State>& one, const std::vector<pba::State>& two)
{
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
        EXPECT_EQ(one[i].pos, two[i].pos) << i;
        EXPECT_EQ(one[i].vel, two[i].vel) << i;
    }
}

} // namespace

TEST(BallOnSegment, AnElasticBallOfTwiceAnEndsMassStopsAndGivesBothEndsItsVelocity)
{
    pba::Scene scene = ballOntoALink("1");
    pba::World& world = scene.world;
    for (int step = 0; step < 500; ++step)
        world.step(scene.dt);
    const std::size_t ball = named(world, "ball");
    EXPECT_NEAR(glm::length(world.body(ball).getVel()), 0.0, 1e-9);
    for (const char* end : {"link[0]", "link[1]"})
        EXPECT_NEAR(glm::length(world.body(named(world, end)).getVel() - dvec3(0, -1, 0)), 0.0, 1e-9) << end;
    EXPECT_GT(world.body(ball).getPos().y - world.body(named(world, "link[0]")).getPos().y, 0.07 - 1e-9) << "apart";
    EXPECT_EQ(world.bounceCount(ball), 1u);
}

TEST(BallOnSegment, WithRestitutionAHalfTheBallKeepsAQuarterOfItsVelocity)
{
    pba::Scene scene = ballOntoALink("0.5");
    pba::World& world = scene.world;
    for (int step = 0; step < 500; ++step)
        world.step(scene.dt);
    // Equal masses 2m and 2m: the ball (1 - e)/2, the point (1 + e)/2 of the velocity.
    EXPECT_NEAR(glm::length(world.body(named(world, "ball")).getVel() - dvec3(0, -0.25, 0)), 0.0, 1e-9);
    for (const char* end : {"link[0]", "link[1]"})
        EXPECT_NEAR(glm::length(world.body(named(world, end)).getVel() - dvec3(0, -0.75, 0)), 0.0, 1e-9) << end;
}

// A cell of a sheet: four 0.1 kg balls of 2 cm radius at the corners of a 30 cm square, in no
// gravity, and a 0.3 kg ball of 3 cm radius coming down at 1 m/s onto the centroid of one of the
// cell's two triangles (whose hole, 8.8 cm to its sides, it would pass through by its balls and
// segments alone).
TEST(BallOnSegment, AnElasticBallOfThreeTimesAnEndsMassStopsOnATrianglesCentroid)
{
    const auto sceneWithBallAt = [](const dvec3& at) {
        return pba::parseScene(
            R"({"dt": 0.001, "gravity": [0, 0, 0], "room": {"min": [-3, -3, -3], "max": [3, 3, 3]},
                "cloths": [{"name": "cell", "origin": [-0.15, 0, -0.15], "across": [0.3, 0, 0], "down": [0, 0, 0.3],
                            "columns": 2, "rows": 2, "mass": 0.4, "stiffness": {"structural": 10, "shear": 1, "bending": 0},
                            "radius": 0.02, "restitution": 1}],
                "particles": [{"name": "ball", "position": [)" +
                std::to_string(at.x) + ", " + std::to_string(at.y) + ", " + std::to_string(at.z) +
                R"(], "velocity": [0, -1, 0], "mass": 0.3, "radius": 0.03, "restitution": 1}]})",
            "ball-onto-a-cell.json");
    };
    // The triangle drawn from the cell's first corner to its opposite one, and its third ball.
    const char* triangle[] = {"cell[0,0]", "cell[0,1]", "cell[1,1]"};
    pba::Scene probe = sceneWithBallAt(dvec3(2, 2, 2));
    dvec3 centroid(0.0);
    for (const char* end : triangle)
        centroid += probe.world.body(named(probe.world, end)).getPos() / 3.0;
    pba::Scene scene = sceneWithBallAt(centroid + dvec3(0, 0.1, 0));
    pba::World& world = scene.world;
    const std::size_t ball = named(world, "ball");
    while (world.body(ball).getVel().y < -0.5)
        world.step(scene.dt);
    EXPECT_NEAR(glm::length(world.body(ball).getVel()), 0.0, 1e-9);
    for (const char* end : triangle)
        EXPECT_NEAR(glm::length(world.body(named(world, end)).getVel() - dvec3(0, -1, 0)), 0.0, 1e-9) << end;
    EXPECT_NEAR(glm::length(world.body(named(world, "cell[1,0]")).getVel()), 0.0, 1e-9);
}

// The same link and ball, the ball at 10 m/s from 25 cm above at dt 1/60 s: it goes 17 cm a step,
// from 18 cm above the link to 8 cm below it, past it by more than the two are thick. It meets the
// link at its time of impact all the same, and the same oracle holds: it stops, the ends leave at
// its velocity, and it ends the step on its side of the link, touching it.
TEST(BallOnSegment, ABallThatWouldGoThroughALinkInOneStepMeetsIt)
{
    for (const char* e : {"1", "0.5"}) {
        pba::Scene scene = pba::parseScene(
            R"({"dt": 0.016666666666666666, "gravity": [0, 0, 0], "room": {"min": [-3, -3, -3], "max": [3, 3, 3]},
                "ropes": [{"name": "link", "from": [-0.15, 0, 0], "to": [0.15, 0, 0], "count": 2, "mass": 0.2,
                           "stiffness": 100, "radius": 0.02, "restitution": )" + std::string(e) + R"(}],
                "particles": [{"name": "ball", "position": [0, 0.25, 0], "velocity": [0, -10, 0], "mass": 0.2,
                               "radius": 0.05, "restitution": )" + e + R"(}]})",
            "fast-ball-onto-a-link.json");
        pba::World& world = scene.world;
        for (int step = 0; step < 2; ++step)
            world.step(scene.dt);
        const double restitution = std::stod(e);
        const std::size_t ball = named(world, "ball");
        EXPECT_NEAR(world.body(ball).getVel().y, -10.0 * (1.0 - restitution) / 2.0, 1e-9) << e;
        for (const char* end : {"link[0]", "link[1]"})
            EXPECT_NEAR(glm::length(world.body(named(world, end)).getVel() - dvec3(0, -10.0 * (1.0 + restitution) / 2.0, 0)),
                        0.0, 1e-9) << end << " " << e;
        const double above = world.body(ball).getPos().y - world.body(named(world, "link[0]")).getPos().y;
        EXPECT_GT(above, 0.07 - 1e-9) << e;
        EXPECT_LT(above, 0.07 + 1e-6) << e;
        EXPECT_EQ(world.bounceCount(ball), 1u);
    }
}

// The cell and ball above at dt 1/60 s, the ball at 10 m/s from 25 cm above the centroid: it would
// go through the triangle in its second step; it meets it at its time of impact and stops there,
// the triangle's balls leaving at its velocity, the cell's fourth still.
TEST(BallOnSegment, ABallThatWouldGoThroughATriangleInOneStepMeetsIt)
{
    const auto scene = [](const std::string& ball) {
        return pba::parseScene(
            R"({"dt": 0.016666666666666666, "gravity": [0, 0, 0], "room": {"min": [-3, -3, -3], "max": [3, 3, 3]},
                "cloths": [{"name": "cell", "origin": [-0.15, 0, -0.15], "across": [0.3, 0, 0], "down": [0, 0, 0.3],
                            "columns": 2, "rows": 2, "mass": 0.4, "stiffness": {"structural": 10, "shear": 1, "bending": 0},
                            "radius": 0.02, "restitution": 1}],
                "particles": [)" + ball + R"(]})",
            "fast-ball-onto-a-cell.json");
    };
    const char* triangle[] = {"cell[0,0]", "cell[0,1]", "cell[1,1]"};
    pba::Scene probe = scene("");
    dvec3 centroid(0.0);
    for (const char* end : triangle)
        centroid += probe.world.body(named(probe.world, end)).getPos() / 3.0;
    const dvec3 start = centroid + dvec3(0, 0.25, 0);
    pba::Scene fast = scene(R"({"name": "ball", "position": [)" + std::to_string(start.x) + ", " +
                            std::to_string(start.y) + ", " + std::to_string(start.z) +
                            R"(], "velocity": [0, -10, 0], "mass": 0.3, "radius": 0.03, "restitution": 1})");
    pba::World& world = fast.world;
    for (int step = 0; step < 2; ++step)
        world.step(fast.dt);
    EXPECT_NEAR(glm::length(world.body(named(world, "ball")).getVel()), 0.0, 1e-9);
    for (const char* end : triangle)
        EXPECT_NEAR(glm::length(world.body(named(world, end)).getVel() - dvec3(0, -10, 0)), 0.0, 1e-9) << end;
    EXPECT_NEAR(glm::length(world.body(named(world, "cell[1,0]")).getVel()), 0.0, 1e-9);
}

// A tightrope of five 2 cm balls 30 cm apart, pinned at both ends 1 m up, and a 5 cm ball dropped
// from half a metre above the middle of its second link: the ball lands on the rope and stays on
// it for 10 s (without its segments it fell between two balls to the floor), above its lowest
// ball by more than the ball's radius.
TEST(BallOnSegment, ABallDroppedOnATightropeBetweenItsBallsStaysOnIt)
{
    pba::Scene scene = pba::parseScene(
        R"({"dt": 0.002, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
            "ropes": [{"name": "rope", "from": [-0.6, 1, 0], "to": [0.6, 1, 0], "count": 5, "mass": 0.5,
                       "pinned": ["start", "end"], "stiffness": 2000, "damping": 2, "radius": 0.02,
                       "friction": 0.5, "restitution": 0}],
            "particles": [{"name": "ball", "position": [0.15, 1.5, 0], "mass": 0.1, "radius": 0.05,
                           "friction": 0.5, "restitution": 0}]})",
        "ball-on-a-tightrope.json");
    pba::World& world = scene.world;
    const std::size_t ball = named(world, "ball");
    double lowest = INFINITY;
    for (int step = 0; step < 5000; ++step) {
        world.step(scene.dt);
        lowest = std::min(lowest, world.body(ball).getPos().y);
    }
    // The rope sags under it by a few centimetres; it ends above the rope's lowest ball.
    double ropeLowest = INFINITY;
    for (int i = 0; i < 5; ++i)
        ropeLowest = std::min(ropeLowest, world.body(named(world, "rope[" + std::to_string(i) + "]")).getPos().y);
    EXPECT_GT(lowest, 0.85);
    EXPECT_GT(world.body(ball).getPos().y, ropeLowest + 0.05);
}

// A sheet of 12 x 12 balls of 1.5 cm radius 18 cm apart, pinned at its corners, and a 4 cm ball
// dropped onto the middle of one of its cells (through whose triangles' holes it fits): it stays
// on the sheet.
TEST(BallOnSegment, ABallDroppedIntoASparseSheetsCellStaysOnIt)
{
    pba::Scene scene = pba::parseScene(
        R"({"dt": 0.002, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
            "cloths": [{"name": "net", "origin": [-1, 1.2, -1], "across": [2, 0, 0], "down": [0, 0, 2], "columns": 12,
                        "rows": 12, "mass": 1, "stiffness": {"structural": 200, "shear": 20, "bending": 0.5},
                        "damping": 0.5, "pinned": ["top-left", "top-right", "bottom-left", "bottom-right"],
                        "radius": 0.015, "friction": 0.4, "restitution": 0}],
            "particles": [{"name": "ball", "position": [0.06, 1.6, 0.03], "mass": 0.05, "radius": 0.04,
                           "friction": 0.4, "restitution": 0}]})",
        "ball-into-a-net.json");
    pba::World& world = scene.world;
    const std::size_t ball = named(world, "ball");
    for (int step = 0; step < 1500; ++step)
        world.step(scene.dt);
    double netLowest = INFINITY;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (i != ball)
            netLowest = std::min(netLowest, world.body(i).getPos().y);
    EXPECT_GT(world.body(ball).getPos().y, netLowest) << "above the sheet's lowest ball";
}

// Link A along x at rest, link B along z 30 cm above it coming down at 1 m/s: their middles meet.
TEST(BallOnSegment, TwoEqualElasticLinksCrossingAtTheirMiddlesExchangeVelocities)
{
    pba::Scene scene = pba::parseScene(R"({"dt": 0.001, "gravity": [0, 0, 0], "room": {"min": [-3, -3, -3], "max": [3, 3, 3]},
        "ropes": [{"name": "a", "from": [-0.15, 0, 0], "to": [0.15, 0, 0], "count": 2, "mass": 0.2,
                   "stiffness": 100, "radius": 0.02, "restitution": 1},
                  {"name": "b", "from": [0, 0.3, -0.15], "to": [0, 0.3, 0.15], "count": 2, "mass": 0.2,
                   "stiffness": 100, "radius": 0.02, "restitution": 1}]})",
                                       "crossing-links.json");
    pba::World& world = scene.world;
    for (const char* end : {"b[0]", "b[1]"})
        world.body(named(world, end)).setVel(dvec3(0, -1, 0));
    for (int step = 0; step < 500; ++step)
        world.step(scene.dt);
    for (const char* end : {"b[0]", "b[1]"})
        EXPECT_NEAR(glm::length(world.body(named(world, end)).getVel()), 0.0, 1e-9) << end;
    for (const char* end : {"a[0]", "a[1]"})
        EXPECT_NEAR(glm::length(world.body(named(world, end)).getVel() - dvec3(0, -1, 0)), 0.0, 1e-9) << end;
    EXPECT_GT(world.body(named(world, "b[0]")).getPos().y - world.body(named(world, "a[0]")).getPos().y, 0.04 - 1e-9)
        << "apart";
}

// A rope of four balls dropped across a tightrope of five, crossing it between two of its balls
// and between two of its own: it hangs on it (without the crossing it fell to the floor), the
// same on one and two threads.
TEST(BallOnSegment, ARopeDroppedAcrossATightropeWhereNeitherHasABallHangsOnIt)
{
    const std::string json =
        R"({"dt": 0.002, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
            "ropes": [{"name": "tightrope", "from": [-0.6, 1, 0], "to": [0.6, 1, 0], "count": 5, "mass": 0.5,
                       "pinned": ["start", "end"], "stiffness": 2000, "damping": 20, "radius": 0.02,
                       "restitution": 0, "friction": 0.5},
                      {"name": "short", "from": [0.15, 1.3, -0.3], "to": [0.15, 1.3, 0.3], "count": 4,
                       "mass": 0.2, "stiffness": 2000, "damping": 5, "radius": 0.03, "restitution": 0,
                       "friction": 0.5}]})";
    const auto one = statesAfter(json, 1500, 1);
    expectSameStates(one, statesAfter(json, 1500, 2));
    for (std::size_t i = 5; i < one.size(); ++i) // the short rope's
        EXPECT_GT(one[i].pos.y, 0.5) << i;
}

// Small balls rain onto a sparse sheet of more balls than a task's grain (2,048), so two threads
// split the grid's search.
TEST(BallOnSegment, ResultsAreTheSameOnOneAndTwoThreads)
{
    std::string balls;
    for (int i = 0; i < 40; ++i)
        balls += std::string(i ? ", " : "") + R"({"name": "b)" + std::to_string(i) + R"(", "position": [)" +
                 std::to_string(-1.5 + 0.077 * i) + ", 1.3, " + std::to_string(-1.2 + 0.061 * i) +
                 R"(], "mass": 0.01, "radius": 0.015, "friction": 0.3})";
    const std::string json =
        R"({"dt": 0.002, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
            "cloths": [{"name": "sheet", "origin": [-1.6, 1.2, -1.6], "across": [3.2, 0, 0], "down": [0, 0, 3.2],
                        "columns": 48, "rows": 48, "mass": 20, "stiffness": {"structural": 50, "shear": 5,
                        "bending": 0.1}, "pinned": ["top-left", "top-right", "bottom-left", "bottom-right"],
                        "radius": 0.005, "friction": 0.3}],
            "particles": [)" + balls + "]}";
    expectSameStates(statesAfter(json, 40, 1), statesAfter(json, 40, 2));
}
