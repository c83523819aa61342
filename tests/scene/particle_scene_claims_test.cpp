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

SCENE_CLAIM(SceneClaims, BallsInTheDryerJostleInTheJetWithoutPassingThroughEachOther, "balls-in-the-dryer")
{
    Scene scene = loadScene("balls-in-the-dryer");
    World& world = scene.world;
    ASSERT_EQ(world.bodyCount(), 5u);
    const int steps = int(std::lround(12.0 / scene.dt)); // 12 s of the minute: caught, then jostling
    int touchingSteps = 0;
    double deepest = 0.0;
    for (int step = 1; step <= steps; ++step) {
        world.step(scene.dt);
        bool touching = false;
        for (std::size_t i = 0; i < 5; ++i) {
            const auto& a = static_cast<const Particle&>(world.body(i));
            if (step * scene.dt > 2.0) { // caught within 2 s: near the axis, high in the jet from then on
                EXPECT_LT(std::hypot(a.getPos().x, a.getPos().z), 1.0) << a.getName() << " at step " << step;
                EXPECT_GT(a.getPos().y, 1.5) << a.getName() << " at step " << step;
            }
            for (std::size_t j = i + 1; j < 5; ++j) {
                const auto& b = static_cast<const Particle&>(world.body(j));
                const double gap = glm::length(b.getPos() - a.getPos()) - a.getRadius() - b.getRadius();
                deepest = std::max(deepest, -gap / std::min(a.getRadius(), b.getRadius()));
                touching |= gap < 1e-3;
            }
        }
        touchingSteps += touching ? 1 : 0;
    }
    EXPECT_LT(deepest, 0.01) << "no ball inside another by a hundredth of its radius";
    EXPECT_GT(touchingSteps, steps / 10) << "they jostle: some pair touches at least a tenth of the time";
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
