// The `ropes` and `cloths` scene keys: what they build (particles, springs, pins), what they
// refuse, and the built-in rope and cloth scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "pba/forces.hpp"
#include "pba/spring_network.hpp"
#include "pba/scene/scene.hpp"
#include "support/scene_claim.hpp"

using namespace pba;

namespace {

std::string roomScene(const std::string& key, const std::string& body)
{
    return fmt::format(R"({{ "room": {{ "min": [-3, 0, -3], "max": [3, 4, 3] }}, "{}": [ {} ] }})", key, body);
}

std::string cloth(int columns, int rows, const std::string& extra = "")
{
    return roomScene("cloths", fmt::format(R"({{ "name": "c", "origin": [-1, 3, -1], "across": [2, 0, 0],
        "down": [0, 0, 2], "columns": {}, "rows": {}, "stiffness": {{ "structural": 100, "shear": 20,
        "bending": 5 }} {} }})", columns, rows, extra));
}

/// The springs of a world's networks (a rope's or cloth's), each one's ends and settings.
std::vector<SpringNetwork::Link> networkSprings(const World& world)
{
    std::vector<SpringNetwork::Link> links;
    for (std::size_t i = 0; i < world.forceCount(); ++i)
        if (const auto* network = dynamic_cast<const SpringNetwork*>(&world.force(i)))
            for (std::size_t s = 0; s < network->size(); ++s)
                links.push_back(network->link(s));
    return links;
}

/// The springs of a world's networks counted by stiffness (each kind of cloth spring has its own).
std::size_t springsOfStiffness(const World& world, double stiffness)
{
    const auto links = networkSprings(world);
    return std::size_t(std::count_if(links.begin(), links.end(), [&](const auto& l) { return l.stiffness == stiffness; }));
}

std::string errorField(const std::string& json)
{
    try {
        parseScene(json, "test");
    } catch (const SceneError& error) {
        return error.field();
    }
    return "(no error)";
}

} // namespace

TEST(Fabric, ClothBuildsItsGridAndEachKindOfSpring)
{
    for (const auto& [w, h] : {std::pair{2, 2}, std::pair{3, 5}, std::pair{7, 4}}) {
        const Scene scene = parseScene(cloth(w, h), "test");
        const World& world = scene.world;
        ASSERT_EQ(world.bodyCount(), std::size_t(w * h));
        EXPECT_EQ(springsOfStiffness(world, 100), std::size_t(w * (h - 1) + h * (w - 1))) << w << "x" << h;
        EXPECT_EQ(springsOfStiffness(world, 20), std::size_t(2 * (w - 1) * (h - 1))) << w << "x" << h;
        EXPECT_EQ(springsOfStiffness(world, 5), std::size_t(w * (h - 2) + h * (w - 2))) << w << "x" << h;
        ASSERT_EQ(scene.fabric.cloths.size(), 1u);
        EXPECT_EQ(scene.fabric.cloths[0].width, std::size_t(w));
        EXPECT_EQ(scene.fabric.cloths[0].height, std::size_t(h));
        EXPECT_EQ(scene.fabric.cloths[0].first, 0u);
        // Row by row from the origin: (i, j) at origin + i/(w-1) across + j/(h-1) down.
        EXPECT_EQ(world.body(scene.fabric.cloths[0].at(w - 1, h - 1)).getPos(), dvec3(1, 3, 1));
        EXPECT_EQ(world.body(1).getName(), "c[1,0]");
    }
}

TEST(Fabric, ClothSpringsStartAtRest)
{
    const Scene scene = parseScene(cloth(4, 4), "test");
    const auto links = networkSprings(scene.world);
    ASSERT_FALSE(links.empty());
    for (const SpringNetwork::Link& l : links)
        EXPECT_DOUBLE_EQ(l.restLength, glm::length(scene.world.body(l.a).getPos() - scene.world.body(l.b).getPos()));
}

TEST(Fabric, ClothPinsByCornerNameAndGridIndex)
{
    const Scene scene = parseScene(cloth(4, 3, R"(, "pinned": ["top-right", "bottom-left", [1, 1]])"), "test");
    const ClothLayout& c = scene.fabric.cloths.at(0);
    std::vector<std::size_t> fixed;
    for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
        if (scene.world.body(i).isFixed())
            fixed.push_back(i);
    EXPECT_EQ(fixed, (std::vector<std::size_t>{c.at(3, 0), c.at(1, 1), c.at(0, 2)}));
}

TEST(Fabric, RopeBuildsStretchAndBendingSpringsAndPinsItsEnds)
{
    const Scene scene = parseScene(roomScene("ropes", R"({ "name": "r", "from": [-2, 3, 0], "to": [2, 3, 0],
        "count": 9, "mass": 0.9, "stiffness": 300, "bending_stiffness": 4, "pinned": ["start", "end"] })"), "test");
    const World& world = scene.world;
    ASSERT_EQ(world.bodyCount(), 9u);
    EXPECT_EQ(springsOfStiffness(world, 300), 8u);
    EXPECT_EQ(springsOfStiffness(world, 4), 7u);
    EXPECT_DOUBLE_EQ(world.body(3).getMass(), 0.1);
    EXPECT_EQ(world.body(4).getPos(), dvec3(0, 3, 0));
    for (std::size_t i = 0; i < 9; ++i)
        EXPECT_EQ(world.body(i).isFixed(), i == 0 || i == 8) << i;
    ASSERT_EQ(scene.fabric.ropes.size(), 1u);
    EXPECT_EQ(scene.fabric.ropes[0].particles.size(), 9u);

    const Scene plain = parseScene(roomScene("ropes", R"({ "name": "r", "from": [-2, 3, 0], "to": [2, 3, 0],
        "count": 2, "stiffness": 300 })"), "test");
    EXPECT_EQ(plain.world.forceCount(), 2u); // gravity and the one stretch spring: no bending without its stiffness
    EXPECT_FALSE(plain.world.body(0).isFixed());
}

TEST(Fabric, BadKeysNameTheirField)
{
    EXPECT_EQ(errorField(cloth(1, 4)), "cloths[0].columns");
    EXPECT_EQ(errorField(cloth(4, 1)), "cloths[0].rows");
    EXPECT_EQ(errorField(cloth(4, 4, R"(, "pinned": ["top-middle"])")), "cloths[0].pinned");
    EXPECT_EQ(errorField(cloth(4, 4, R"(, "pinned": [[4, 0]])")), "cloths[0].pinned");
    EXPECT_EQ(errorField(cloth(4, 4, R"(, "pinned": [[0, -1]])")), "cloths[0].pinned");
    EXPECT_EQ(errorField(roomScene("cloths", R"({ "name": "c", "origin": [-1, 3, -1], "across": [2, 0, 0],
        "down": [0, 0, 2], "columns": 3, "rows": 3, "stiffness": { "structral": 1 } })")),
              "cloths[0].stiffness.structral");
    EXPECT_EQ(errorField(roomScene("ropes", R"({ "name": "r", "from": [-2, 3, 0], "to": [2, 3, 0], "count": 1,
        "stiffness": 3 })")), "ropes[0].count");
    EXPECT_EQ(errorField(roomScene("ropes", R"({ "name": "r", "from": [-2, 3, 0], "to": [2, 3, 0], "count": 4,
        "stiffness": 3, "pinned": ["middle"] })")), "ropes[0].pinned");
    EXPECT_EQ(errorField(roomScene("ropes", R"({ "name": "r", "from": [-2, 3, 0], "to": [9, 3, 0], "count": 4,
        "stiffness": 3 })")), "ropes[0].to"); // its far end outside the room
    // A rope particle whose energy overflows is named by its rope, not as particles[i].
    EXPECT_EQ(errorField(R"({ "ropes": [ { "name": "r", "from": [0, 1e300, 0], "to": [0, 1.5e300, 0],
        "count": 3, "mass": 1e10, "stiffness": 3 } ] })"), "ropes[0]");
}

TEST(Fabric, BuiltInScenesLoadAndRunFinite)
{
    for (const char* name : {"rope", "cloth", "cloth-in-the-dryer"}) {
        Scene scene = loadScene(name);
        EXPECT_FALSE(scene.fabric.empty()) << name;
        for (int n = 0; n < 200; ++n)
            scene.world.step(scene.dt);
        for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
            EXPECT_TRUE(std::isfinite(scene.world.body(i).getPos().y)) << name << " " << i;
    }
}

// The built-in rope's claim: "it swings down, the particles at its free end strike the floor ...
// and it ends hanging below its pin with its last particles on the floor, having lost energy".
SCENE_CLAIM(Fabric, RopeSwingsDownToTheFloorAndHangsBelowItsPin, "rope")
{
    Scene scene = loadScene("rope");
    World& world = scene.world;
    const std::size_t end = scene.fabric.ropes.at(0).particles.back();
    double lowest = world.body(end).getPos().y;
    const double e0 = world.totalEnergy();
    for (long n = 0; n < std::lround(scene.duration / scene.dt); ++n) {
        world.step(scene.dt);
        lowest = std::min(lowest, world.body(end).getPos().y);
    }
    EXPECT_LT(lowest, 1e-3); // the free end reaches the floor
    EXPECT_LT(world.body(end).getPos().y, 1e-3);
    EXPECT_EQ(world.body(0).getPos(), dvec3(-2.5, 3.5, 0)); // the pin holds
    EXPECT_NEAR(world.body(1).getPos().x, -2.5, 0.05);      // the rope hangs from it
    EXPECT_LT(world.totalEnergy(), e0);
}

// "A cloth resting pinned settles (kinetic energy decays with damping) and never leaves the
// room", and the scene's description: over the built-in scene's run, the kinetic energy after the fall dies away to a small
// fraction of its peak, each second's mean below the one before from the third second on, and
// every particle stays inside the room (a point on its walls counts as inside) at every step.
SCENE_CLAIM(Fabric, PinnedClothSettlesAndNeverLeavesTheRoom, "cloth")
{
    Scene scene = loadScene("cloth");
    World& world = scene.world;
    const Aabb room = *world.room();
    auto kinetic = [&] {
        double sum = 0.0;
        for (std::size_t i = 0; i < world.bodyCount(); ++i)
            sum += world.kineticEnergy(i);
        return sum;
    };
    const int perSecond = static_cast<int>(std::lround(1.0 / scene.dt));
    const int seconds = static_cast<int>(std::lround(scene.duration));
    double peak = 0.0;
    std::vector<double> meanPerSecond;
    for (int s = 0; s < seconds; ++s) {
        double sum = 0.0;
        for (int n = 0; n < perSecond; ++n) {
            world.step(scene.dt);
            const double k = kinetic();
            peak = std::max(peak, k);
            sum += k;
            for (std::size_t i = 0; i < world.bodyCount(); ++i) {
                const dvec3 x = world.body(i).getPos();
                ASSERT_TRUE(x.x >= room.min.x && x.y >= room.min.y && x.z >= room.min.z && x.x <= room.max.x &&
                            x.y <= room.max.y && x.z <= room.max.z)
                    << world.body(i).getName() << " left the room at t = " << world.time();
            }
        }
        meanPerSecond.push_back(sum / perSecond);
    }
    ASSERT_GT(peak, 0.5); // it did fall
    for (std::size_t s = 3; s < meanPerSecond.size(); ++s)
        EXPECT_LT(meanPerSecond[s], meanPerSecond[s - 1]) << "second " << s;
    EXPECT_LT(kinetic(), 0.01 * peak);
    // The description's "its two lowest rows striking the room's back wall ... (from 1 to 22
    // bounces each, no other particle touching a surface) ... its free edge 1.45 to 1.46 m up and every
    // particle slower than 2 cm/s at the end".
    const auto& sheet = scene.fabric.cloths.at(0);
    for (std::size_t row = 0; row < 12; ++row)
        for (std::size_t column = 0; column < 12; ++column) {
            const std::size_t i = sheet.at(column, row);
            if (row >= 10) {
                EXPECT_GE(world.bounceCount(i), 1u) << world.body(i).getName();
                EXPECT_LE(world.bounceCount(i), 22u) << world.body(i).getName();
            } else {
                EXPECT_EQ(world.bounceCount(i), 0u) << world.body(i).getName();
            }
            EXPECT_LT(glm::length(world.body(i).getVel()), 0.05) << world.body(i).getName();
            if (row == 11) {
                EXPECT_NEAR(world.body(i).getPos().y, 1.455, 0.01) << world.body(i).getName();
            }
        }
    EXPECT_TRUE(world.body(scene.fabric.cloths.at(0).at(0, 0)).isFixed());
    EXPECT_EQ(world.body(scene.fabric.cloths.at(0).at(0, 0)).getPos(), dvec3(-1, 3.5, -1));
}

// The bench's cloth, smaller: one system of 4,096 particles and about 24,000 springs, enough
// that every parallel loop of the step splits into several tasks. Its states after a third of a
// second are the same to the bit on 1 thread and on 2, and the sheet behaves as the 10 x 10
// built-in does (held up in the jet, not blown apart: the scaling keeps it stable).
TEST(Fabric, ResizedClothStepsTheSameOnAnyNumberOfThreads)
{
    Scene scene = resizedClothInTheDryer(64);
    ASSERT_EQ(scene.world.bodyCount(), 64u * 64u);
    World one = scene.world;
    World two = scene.world;
    one.setThreads(1);
    two.setThreads(2);
    for (int n = 0; n < 150; ++n) {
        one.step(scene.dt);
        two.step(scene.dt);
    }
    double lowest = INFINITY;
    for (std::size_t i = 0; i < one.bodyCount(); ++i) {
        ASSERT_EQ(one.body(i).getPos(), two.body(i).getPos()) << one.body(i).getName();
        ASSERT_EQ(one.body(i).getVel(), two.body(i).getVel()) << one.body(i).getName();
        ASSERT_EQ(one.body(i).getAcc(), two.body(i).getAcc()) << one.body(i).getName();
        ASSERT_EQ(one.bounceCount(i), two.bounceCount(i)) << one.body(i).getName();
        lowest = std::min(lowest, one.body(i).getPos().y);
    }
    EXPECT_GT(lowest, 2.5); // in the jet above the floor, as the built-in's sheet
}

TEST(Fabric, ResizedClothNeedsTwoParticlesASide)
{
    EXPECT_THROW(resizedClothInTheDryer(1), std::invalid_argument);
}
