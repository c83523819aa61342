// XPBD's ropes and cloths meet rigid bodies and each other inside their substeps (src/core/particle_systems/xpbd.hpp,
// xpbd_rigid_contacts.hpp). Oracles: the pushes between a sheet and a box are equal and opposite,
// so with no gravity and no wall reached their total momentum stays what it was (to rounding)
// while each changes the other's; a ball dropped on a fixed box rises to e^2 h; a ball resting on
// a ball resting on the floor stays put; and the trampoline's crate, which XPBD's sheet threw off
// when the two met only after the step, is caught, thrown back up and held; a sheet fallen on a
// bed of blocks, fixed or free (looked up in a grid), is never inside one. (A sheet fallen in
// folds resting on itself: tests/core/resting_cloth_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pba/rigid_body.hpp"
#include "pba/scene/scene.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

dvec3 momentum(const World& world)
{
    dvec3 total(0.0);
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (!world.body(i).isFixed())
            total += world.body(i).getMass() * world.body(i).getVel();
    return total;
}

/// The trampoline scene with its sheet stepped by XPBD.
Scene xpbdTrampoline(int threads)
{
    Scene scene = loadScene("trampoline");
    for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
        if (!scene.world.isRigid(i))
            scene.world.body(i).setIntegrator(Integrator::Xpbd);
    scene.world.setThreads(threads);
    return scene;
}

} // namespace

TEST(XpbdContact, ASheetAndABoxExchangeMomentumAndKeepItsTotal)
{
    // A free 8 x 8 sheet at rest in the middle of a large room, no gravity, and a 2 kg box moving
    // into it at 2 m/s: it drives the sheet on and is slowed by it.
    const std::string text = R"({"dt": 0.002, "gravity": [0, 0, 0], "room": {"min": [-10, -10, -10], "max": [10, 10, 10]},
        "cloths": [{"name": "sheet", "origin": [-0.35, 0, -0.35], "across": [0.7, 0, 0], "down": [0, 0, 0.7],
                    "columns": 8, "rows": 8, "mass": 0.5, "stiffness": {"structural": 5000, "shear": 500, "bending": 1},
                    "damping": 1, "integrator": "xpbd", "restitution": 0, "friction": 0.5, "radius": 0.05}],
        "rigid_bodies": [{"name": "box", "shape": {"type": "box", "size": [0.3, 0.3, 0.3]}, "mass": 2,
                          "position": [0.05, 0.5, 0.02], "velocity": [0, -2, 0], "friction": 0.5, "restitution": 0}]})";
    Scene scene = parseScene(text, "push.json");
    World& world = scene.world;
    const dvec3 before = momentum(world);
    const std::size_t box = *world.findBody("box");
    for (int step = 0; step < 300; ++step) {
        world.step(scene.dt);
        ASSERT_LT(glm::length(momentum(world) - before), 1e-9 * glm::length(before)) << "step " << step;
    }
    EXPECT_GT(world.body(box).getVel().y, -1.9) << "the sheet slowed the box";
    EXPECT_LT(world.body(*world.findBody("sheet[3,3]")).getVel().y, -0.1) << "the box drove the sheet on";
}

TEST(XpbdContact, ABallDroppedOnAFixedBoxReboundsToESquaredTimesItsFall)
{
    // As off the room: it leaves at e times the speed it arrived with, so it rises to e^2 h.
    const std::string text = R"({"dt": 0.002, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "particles": [{"name": "ball", "position": [0, 1.5, 0], "mass": 0.1, "radius": 0.05, "restitution": 0.5,
                       "integrator": "xpbd"}],
        "rigid_bodies": [{"name": "table", "shape": {"type": "box", "size": [0.5, 0.5, 0.5]}, "position": [0, 0.25, 0],
                          "fixed": true, "restitution": 0}]})";
    Scene scene = parseScene(text, "drop.json");
    World& world = scene.world;
    const std::size_t ball = *world.findBody("ball");
    const double fall = 1.5 - 0.05 - 0.5; // to the table's top
    double highest = 0.0;
    bool bounced = false;
    for (int step = 0; step < 1000; ++step) { // 2 s: one bounce and most of the next
        world.step(scene.dt);
        const dvec3 v = world.body(ball).getVel();
        bounced = bounced || v.y > 0.0;
        if (bounced && world.body(ball).getPos().y > 0.55 + highest && v.y >= 0.0)
            highest = world.body(ball).getPos().y - 0.55;
        if (bounced && v.y < 0.0 && highest > 0.0)
            break;
    }
    EXPECT_NEAR(highest, 0.25 * fall, 0.02 * 0.25 * fall);
    EXPECT_EQ(world.bounceCount(ball), 1u);
}

TEST(XpbdContact, TheTrampolineCatchesItsCrateThrowsItBackUpAndHoldsIt)
{
    Scene scene = xpbdTrampoline(0);
    World& world = scene.world;
    const std::size_t crate = *world.findBody("crate");
    double lowest = INFINITY, rebound = -INFINITY, at8 = 0.0;
    bool landed = false;
    for (int step = 1; step <= 5000; ++step) { // the scene's 10 s
        world.step(scene.dt);
        const double y = world.body(crate).getPos().y;
        lowest = std::min(lowest, y);
        landed = landed || world.body(crate).getVel().y > 0.0;
        if (landed && step * scene.dt < 1.5)
            rebound = std::max(rebound, y);
        if (step == 4000)
            at8 = y;
    }
    // Measured: its bottom no lower than 0.98 m, thrown up 0.64 m, at rest 1.24 m above the floor.
    EXPECT_GT(lowest - 0.2, 0.8) << "its bottom stayed well above the floor";
    EXPECT_GT(rebound - lowest, 0.4) << "thrown back up";
    EXPECT_GT(world.body(crate).getPos().y - 0.2, 1.1) << "held in the sag";
    EXPECT_LT(std::abs(world.body(crate).getPos().y - at8), 1e-3) << "at rest from 8 s to 10 s";
}

TEST(XpbdContact, ABallRestingOnABallRestingOnTheFloorStaysPut)
{
    const std::string text = R"({"dt": 0.001, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 4, 2]},
        "particles": [{"name": "low", "position": [0, 0.1, 0], "mass": 1, "radius": 0.1, "restitution": 0.5,
                       "friction": 0.3, "integrator": "xpbd"},
                      {"name": "high", "position": [0, 0.3, 0], "mass": 1, "radius": 0.1, "restitution": 0.5,
                       "friction": 0.3, "integrator": "xpbd"}]})";
    Scene scene = parseScene(text, "stack.json");
    for (int step = 0; step < 10000; ++step) // 10 s
        scene.world.step(scene.dt);
    EXPECT_LT(glm::length(scene.world.body(0).getPos() - dvec3(0, 0.1, 0)), 1e-4);
    EXPECT_LT(glm::length(scene.world.body(1).getPos() - dvec3(0, 0.3, 0)), 1e-4);
}

TEST(XpbdContact, TheTrampolineIsTheSameOnOneAndTwoThreads)
{
    Scene one = xpbdTrampoline(1), two = xpbdTrampoline(2);
    for (int step = 0; step < 300; ++step) { // landed and thrown back up
        one.world.step(one.dt);
        two.world.step(two.dt);
    }
    for (std::size_t i = 0; i < one.world.bodyCount(); ++i) {
        ASSERT_EQ(one.world.body(i).getPos(), two.world.body(i).getPos()) << i;
        ASSERT_EQ(one.world.body(i).getVel(), two.world.body(i).getVel()) << i;
    }
}

class BedOfBlocks : public ::testing::TestWithParam<bool> {};

TEST_P(BedOfBlocks, ASheetFallenOnItNeverEntersABlock)
{
    // 36 blocks, fixed or free on the floor (so XPBD's members look them up in a grid of cells,
    // built once a step or in every substep, rather than test each): the sheet falls onto them and
    // drapes between them, and no ball's centre is ever inside one.
    const bool fixed = GetParam();
    std::string blocks;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
            blocks += std::string(blocks.empty() ? "" : ",") + R"({"name": "b)" + std::to_string(6 * i + j) +
                      R"(", "shape": {"type": "box", "size": [0.1, 0.3, 0.1]}, "density": 500, "fixed": )" +
                      (fixed ? "true" : "false") + R"(, "position": [)" + std::to_string(-0.625 + 0.25 * i) +
                      ", 0.15, " + std::to_string(-0.625 + 0.25 * j) + "]}";
    const std::string text = R"({"dt": 0.005, "room": {"min": [-2, 0, -2], "max": [2, 2, 2]},
        "cloths": [{"name": "sheet", "origin": [-0.75, 0.8, -0.75], "across": [1.5, 0, 0], "down": [0, 0, 1.5],
                    "columns": 16, "rows": 16, "mass": 0.5, "stiffness": {"structural": 300, "shear": 30, "bending": 2},
                    "damping": 0.05, "integrator": "xpbd", "restitution": 0, "friction": 0.5, "radius": 0.03}],
        "rigid_bodies": [)" + blocks + "]}";
    Scene scene = parseScene(text, "bed.json");
    World& world = scene.world;
    int resting = 0;
    for (int step = 0; step < 300; ++step) {
        world.step(scene.dt);
        for (std::size_t p = 0; p < world.bodyCount(); ++p) {
            if (world.isRigid(p))
                continue;
            const dvec3 x = world.body(p).getPos();
            for (std::size_t b = 0; b < world.bodyCount(); ++b) {
                if (!world.isRigid(b))
                    continue;
                const auto& block = static_cast<const RigidBody&>(world.body(b));
                const dvec3 d = glm::abs(glm::inverse(block.getOrientation()) * (x - block.getPos()));
                ASSERT_FALSE(d.x < 0.05 && d.y < 0.15 && d.z < 0.05)
                    << world.body(p).getName() << " inside " << world.body(b).getName() << " at step " << step;
            }
            if (step == 299 && std::abs(x.y - 0.33) < 0.005)
                ++resting;
        }
    }
    EXPECT_GE(resting, 16) << "the sheet lies on the blocks' tops, a radius above them";
}

INSTANTIATE_TEST_SUITE_P(FixedOrFree, BedOfBlocks, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& blocks) { return blocks.param ? "Fixed" : "Free"; });
