// A cloth resting on the floor, stepped by backward Euler or XPBD: backward Euler's solve holds each
// particle that lies on it (Baraff and Witkin's constraints), XPBD keeps it on the floor in every
// substep, so the springs never pull it into the floor for the rule after the step to push back.
// Oracles: a sheet lying flat and pulled up (gravity reversed) leaves the floor at once and rises
// as any body under a uniform force does under semi-implicit Euler's substeps of h,
// x_m = x_0 + g h^2 m (m + 1) / 2 after m of them, its springs at rest; a sheet sliding on the
// floor with friction mu decelerates at mu g (the push that holds it is its weight), so it stops
// after v0^2 / (2 mu g), lying exactly on the floor; a sheet fallen in folds counts its resting
// particles' contact with the floor as contact, not a bounce a step, and its upper layers rest on
// the lower ones (held on the balls below them by backward Euler, met in XPBD's substeps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pba/scene/scene.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

constexpr double kG = 9.81;
constexpr double kRadius = 0.04;
constexpr double kDt = 0.002;

/// A 10 x 10 sheet lying flat on the floor, its balls touching it, under `gravity`, moving at `velocity`.
Scene lyingSheet(Integrator integrator, double gravityY, double velocityX, double friction)
{
    const std::string text = R"({"dt": 0.002, "gravity": [0, )" + std::to_string(gravityY) +
                             R"(, 0], "collision_response": "reflect", "room": {"min": [-4, 0, -4], "max": [4, 3, 4]},
        "cloths": [{"name": "sheet", "origin": [-0.5, 0.04, -0.5], "across": [1, 0, 0], "down": [0, 0, 1],
                    "columns": 10, "rows": 10, "mass": 0.1, "stiffness": {"structural": 400, "shear": 40, "bending": 1},
                    "damping": 0.05, "restitution": 0, "radius": 0.04, "friction": )" +
                             std::to_string(friction) + R"(, "integrator": ")" +
                             std::string(integratorName(integrator)) + R"("}]})";
    Scene scene = parseScene(text, "lying.json");
    for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
        scene.world.body(i).setVel(dvec3(velocityX, 0.0, 0.0));
    return scene;
}

class RestingCloth : public ::testing::TestWithParam<Integrator> {};

} // namespace

TEST_P(RestingCloth, PulledOffTheFloorItRisesAsAFreeBody)
{
    Scene scene = lyingSheet(GetParam(), kG, 0.0, 0.5);
    World& world = scene.world;
    const int substeps = GetParam() == Integrator::Xpbd ? world.xpbdSubsteps() : 1;
    const double h = kDt / substeps;
    for (int n = 1; n <= 100; ++n) {
        world.step(kDt);
        const double m = double(n) * substeps;
        const double expected = kRadius + kG * h * h * m * (m + 1.0) / 2.0;
        for (std::size_t i = 0; i < world.bodyCount(); ++i)
            ASSERT_NEAR(world.body(i).getPos().y, expected, 1e-9) << "step " << n << ", particle " << i;
    }
}

TEST_P(RestingCloth, SlidingWithFrictionItStopsAfterV0SquaredOverTwoMuGOnTheFloor)
{
    const double mu = 0.5, v0 = 1.0, expected = v0 * v0 / (2.0 * mu * kG);
    Scene scene = lyingSheet(GetParam(), -kG, v0, mu);
    World& world = scene.world;
    std::vector<double> startX;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        startX.push_back(world.body(i).getPos().x);
    for (int n = 0; n < 250; ++n) {
        world.step(kDt);
        for (std::size_t i = 0; i < world.bodyCount(); ++i)
            ASSERT_NEAR(world.body(i).getPos().y, kRadius, 1e-12) << "held on the floor, not in it";
    }
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        EXPECT_NEAR(world.body(i).getPos().x - startX[i], expected, 0.01 * expected);
        EXPECT_LT(glm::length(world.body(i).getVel()), 1e-12) << "it stopped";
        EXPECT_EQ(world.bounceCount(i), 0u) << "resting contact is not a bounce";
    }
}

TEST_P(RestingCloth, ASheetFallenInFoldsRestsOnTheFloorAndOnItself)
{
    // cloth-folds' sheet, settled: its springs pull the particles under the folds toward the floor
    // every step, which the solve takes up (with the room only after the step: about 5,000
    // bounces a second under either method). Its upper layers rest on the lower: measured at 8 s,
    // speeds median 8 mm/s, 95% under 3.4 cm/s (implicit Euler) and median 0.4 mm/s, 95% under
    // 1.2 mm/s (XPBD); with its layers meeting only after the step, the upper ones stirred on the
    // lower: medians 4 and 1.6 cm/s, 95% 12 and 5 cm/s.
    Scene scene = loadScene("cloth-folds");
    World& world = scene.world;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        world.body(i).setIntegrator(GetParam());
    for (int n = 0; n < 2500; ++n)
        world.step(scene.dt);
    std::uint64_t before = 0, after = 0;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        before += world.bounceCount(i);
    for (int n = 0; n < 500; ++n)
        world.step(scene.dt);
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        after += world.bounceCount(i);
    EXPECT_LE(after - before, 20u) << "bounces in a second among 400 resting particles";
    for (int n = 0; n < 1000; ++n)
        world.step(scene.dt);
    std::vector<double> speeds;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        speeds.push_back(glm::length(world.body(i).getVel()));
    std::sort(speeds.begin(), speeds.end());
    EXPECT_LT(speeds[speeds.size() / 2], 0.01);
    EXPECT_LT(speeds[speeds.size() * 95 / 100], 0.06);
}

TEST_P(RestingCloth, HeldOnTheFloorTheSameOnOneAndTwoThreads)
{
    // The holds' choice, their letting go and XPBD's room in the substeps read each particle alone
    // or through sums over a fixed tree: the folds land the same to the bit on any thread count.
    auto fallen = [](int threads) {
        Scene scene = loadScene("cloth-folds");
        World& world = scene.world;
        world.setThreads(threads);
        for (std::size_t i = 0; i < world.bodyCount(); ++i)
            world.body(i).setIntegrator(GetParam());
        for (int n = 0; n < 1000; ++n)
            world.step(scene.dt);
        std::vector<dvec3> state;
        for (std::size_t i = 0; i < world.bodyCount(); ++i) {
            state.push_back(world.body(i).getPos());
            state.push_back(world.body(i).getVel());
        }
        return state;
    };
    EXPECT_EQ(fallen(1), fallen(2));
}

INSTANTIATE_TEST_SUITE_P(Methods, RestingCloth, ::testing::Values(Integrator::ImplicitEuler, Integrator::Xpbd),
                         [](const ::testing::TestParamInfo<Integrator>& method) {
                             return method.param == Integrator::Xpbd ? "Xpbd" : "ImplicitEuler";
                         });

// Only a member lying on a surface is held on it: one a metre and a half above the floor, pulled
// down at 6e5 m/s^2 by a stretched stiff spring (as a sheet's member beside a crate sinking into
// it), moves exactly as with no floor at all. It was held in the air, its fall stopped, because
// a step at its acceleration would have reached the floor.
TEST(RestingCloth, AMemberFarFromTheFloorIsNotHeldOnIt)
{
    auto stretched = [](bool room) {
        const std::string text = std::string(R"({"dt": 0.002, "gravity": [0, -9.81, 0], )") +
                                 (room ? R"("room": {"min": [-4, 0, -4], "max": [4, 3, 4]}, )" : "") +
                                 R"("ropes": [{"name": "r", "from": [0, 1, 0], "to": [0, 1.2, 0], "count": 2,
                                   "mass": 0.02, "stiffness": 20000, "pinned": ["start"], "radius": 0.05,
                                   "integrator": "implicit-euler"}]})";
        Scene scene = parseScene(text, "stretched.json");
        scene.world.body(1).setPos(dvec3(0.0, 1.5, 0.0));
        for (int n = 0; n < 5; ++n)
            scene.world.step(kDt);
        return std::pair(scene.world.body(1).getPos(), scene.world.body(1).getVel());
    };
    const auto [x, v] = stretched(true);
    EXPECT_EQ(x, stretched(false).first);
    EXPECT_EQ(v, stretched(false).second);
    EXPECT_LT(x.y, 1.3) << "it fell towards its rest length";
}
