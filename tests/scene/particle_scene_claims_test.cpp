// The built-in scenes of balls, touching each other and held in the dryer's air, held to their claims.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pba/blow_dryer.hpp"
#include "pba/scene/scene.hpp"
#include "pba/world.hpp"
#include "support/scene_claim.hpp"

using namespace pba;

SCENE_CLAIM(SceneClaims, BallsInTheDryerAreCaughtAndHoverInOneClumpWithoutPassingThroughEachOther,
            "balls-in-the-dryer")
{
    Scene scene = loadScene("balls-in-the-dryer");
    World& world = scene.world;
    ASSERT_EQ(world.bodyCount(), 5u);
    const auto ball = [&](std::size_t i) -> const Particle& { return static_cast<const Particle&>(world.body(i)); };
    const auto gap = [&](std::size_t i, std::size_t j) {
        return glm::length(ball(j).getPos() - ball(i).getPos()) - ball(i).getRadius() - ball(j).getRadius();
    };
    const long steps = std::lround(scene.duration / scene.dt);
    double deepest = 0.0, farthestFromAnother = 0.0, fastestApart = 0.0;
    for (long step = 1; step <= steps; ++step) {
        world.step(scene.dt);
        const double t = double(step) * scene.dt;
        dvec3 mean(0.0);
        for (std::size_t i = 0; i < 5; ++i)
            mean += ball(i).getVel() / 5.0;
        for (std::size_t i = 0; i < 5; ++i) {
            if (t > 2.0) { // caught within 2 s: near the axis, high in the jet from then on
                EXPECT_LT(std::hypot(ball(i).getPos().x, ball(i).getPos().z), 1.0) << ball(i).getName() << " at " << t;
                EXPECT_GT(ball(i).getPos().y, 1.5) << ball(i).getName() << " at " << t;
            }
            double nearest = INFINITY;
            for (std::size_t j = 0; j < 5; ++j)
                if (j != i) {
                    nearest = std::min(nearest, gap(i, j));
                    deepest = std::max(deepest, -gap(i, j) / std::min(ball(i).getRadius(), ball(j).getRadius()));
                }
            if (t >= 2.7) // one clump: each touching another (sim: from 2.6 s)
                farthestFromAnother = std::max(farthestFromAnother, nearest);
            if (t >= 5.0) // and settled in it, all moving as one
                fastestApart = std::max(fastestApart, glm::length(ball(i).getVel() - mean));
        }
    }
    EXPECT_LT(deepest, 0.01) << "no ball inside another by a hundredth of its radius";
    EXPECT_LT(farthestFromAnother, 1e-3) << "from 2.7 s on every ball is within 1 mm of touching another";
    EXPECT_LT(fastestApart, 1e-3) << "from 5 s on the balls move as one, within 1 mm/s";
}

SCENE_CLAIM(SceneClaims, APingPongBallIsCaughtByTheDryersAirAndHovers, "ping-pong")
{
    Scene scene = loadScene("ping-pong");
    World& world = scene.world;
    ASSERT_EQ(world.bodyCount(), 1u);
    const auto& ball = static_cast<const Particle&>(world.body(0));
    const BlowDryerField air = blowDryers(world).at(0).field;
    // Where the air's speed holds its weight: (1/2) rho C_d pi r^2 |u|^2 = m g, |u| = U (1 - h/H).
    const double r = ball.getRadius(), g = 9.81;
    const double held = std::sqrt(2.0 * ball.getMass() * g / (air.airDensity * air.dragCoefficient * std::numbers::pi * r * r));
    const double hover = air.height * (1.0 - held / air.airSpeed);
    EXPECT_NEAR(hover, 0.2796, 1e-4) << "the summary's 0.28 m";
    double lowest = INFINITY;
    const auto steps = std::lround(scene.duration / scene.dt);
    for (long step = 0; step < steps; ++step) {
        world.step(scene.dt);
        lowest = std::min(lowest, ball.getPos().y);
    }
    EXPECT_GT(lowest, 0.05) << "caught: never down at the nozzle";
    EXPECT_NEAR(ball.getPos().y, hover, 1e-3 * hover);
    EXPECT_LT(std::hypot(ball.getPos().x, ball.getPos().z), 1e-3) << "on the axis";
    EXPECT_LT(glm::length(ball.getVel()), 1e-3) << "at rest";
}
