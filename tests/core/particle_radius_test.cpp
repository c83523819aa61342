// A particle's radius against the room. Oracle: a ball of radius r meets a plane where its centre
// is r inside it, so it must follow, to the bit, a point in a room whose every wall is moved r
// inward (the numbers below are powers of two apart, so both rooms' planes are the same numbers).
#include <gtest/gtest.h>

#include <memory>

#include "pba/forces.hpp"
#include "pba/scene/scene.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

constexpr double kRadius = 0.125;

World roomWorld(CollisionResponse response, const Aabb& room, double radius, bool swarm)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
    world.setRoom(room);
    world.setCollisionResponse(response);
    world.setThreads(1);
    if (swarm) {
        SwarmDesc desc;
        desc.name = "grains";
        desc.count = 64;
        desc.regionMin = dvec3(-1.5, 1.0, -1.5);
        desc.regionMax = dvec3(1.5, 3.0, 1.5);
        desc.velocityJitter = 6.0;
        desc.restitution = 0.75;
        desc.radius = radius;
        world.addSwarm(desc);
        return world;
    }
    Particle p;
    p.setPos(dvec3(-1.0, 2.0, 0.5));
    p.setVel(dvec3(7.0, 3.0, -5.0)); // crosses the room, meets walls, floor and ceiling
    p.setCor(0.75);
    p.setRadius(radius);
    world.addParticle(p);
    return world;
}

const Aabb kRoom{dvec3(-2, 0, -2), dvec3(2, 4, 2)};
const Aabb kShrunk{kRoom.min + kRadius, kRoom.max - kRadius};

} // namespace

TEST(ParticleRadius, ABallFollowsAPointInTheRoomShrunkByItsRadius)
{
    for (const CollisionResponse response : kAllCollisionResponses) {
        World ball = roomWorld(response, kRoom, kRadius, false);
        World point = roomWorld(response, kShrunk, 0.0, false);
        for (int step = 0; step < 400; ++step) {
            ball.step(0.01);
            point.step(0.01);
        }
        EXPECT_EQ(ball.body(0).getPos(), point.body(0).getPos()) << collisionResponseName(response);
        EXPECT_EQ(ball.body(0).getVel(), point.body(0).getVel()) << collisionResponseName(response);
        EXPECT_EQ(ball.bounceCount(0), point.bounceCount(0)) << collisionResponseName(response);
        EXPECT_GT(ball.bounceCount(0), 3u) << "the test must exercise the walls";
    }
}

TEST(ParticleRadius, ASwarmsGrainsFollowPointsInTheRoomShrunkByTheirRadius)
{
    for (const CollisionResponse response : kAllCollisionResponses) {
        World grains = roomWorld(response, kRoom, kRadius, true);
        World points = roomWorld(response, kShrunk, 0.0, true);
        for (int step = 0; step < 200; ++step) {
            grains.step(0.01);
            points.step(0.01);
        }
        for (std::size_t i = 0; i < grains.swarm(0).size(); ++i) {
            ASSERT_EQ(grains.swarm(0).position(i), points.swarm(0).position(i)) << collisionResponseName(response);
            ASSERT_GE(grains.swarm(0).position(i).y, float(kRadius)) << "no grain sinks into the floor";
        }
    }
}

TEST(ParticleRadius, ARopeOfBallsLiesOnTheFloorAtItsRadius)
{
    // A rope's particles take the reflect or clamp rule after their system's step.
    Scene scene = parseScene(R"({"dt": 0.002, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 4, 2]},
        "ropes": [{"name": "rope", "from": [-1, 0.5, 0], "to": [1, 0.5, 0], "count": 11, "mass": 0.5,
                   "stiffness": 500, "damping": 1, "restitution": 0, "radius": 0.05, "integrator": "velocity-verlet"}]})",
                             "rope.json");
    for (int step = 0; step < 1000; ++step)
        scene.world.step(scene.dt);
    for (std::size_t i = 0; i < scene.world.bodyCount(); ++i) {
        EXPECT_GE(scene.world.body(i).getPos().y, 0.05);
        EXPECT_LT(scene.world.body(i).getPos().y, 0.05 + 1e-3) << "it fell all the way";
        EXPECT_EQ(static_cast<const Particle&>(scene.world.body(i)).getRadius(), 0.05);
    }
}

TEST(ParticleRadius, NoRadiusIsTheSameRunToTheBitAsRadiusZero)
{
    const std::string body = R"("dt": 0.01, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 4, 2]},
        "particles": [{"name": "a", "position": [0, 1, 0], "velocity": [3, 2, 1], "restitution": 0.5 RADIUS}])";
    auto withRadius = [&](const std::string& radius) {
        std::string text = "{" + body + "}";
        text.replace(text.find("RADIUS"), 6, radius);
        Scene scene = parseScene(text, "a.json");
        for (int step = 0; step < 300; ++step)
            scene.world.step(scene.dt);
        return scene.world.body(0).getState();
    };
    const State absent = withRadius(""), zero = withRadius(R"(, "radius": 0, "friction": 0)");
    EXPECT_EQ(absent.pos, zero.pos);
    EXPECT_EQ(absent.vel, zero.vel);
}

TEST(ParticleRadius, ANegativeOrNotFiniteRadiusOrFrictionIsRefused)
{
    Particle p;
    EXPECT_THROW(p.setRadius(-0.1), std::invalid_argument);
    EXPECT_THROW(p.setRadius(std::numeric_limits<double>::infinity()), std::invalid_argument);
    EXPECT_THROW(p.setFriction(-0.5), std::invalid_argument);
    EXPECT_THROW(p.setFriction(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    p.setRadius(0.02);
    p.setFriction(0.4);
    EXPECT_EQ(p.getRadius(), 0.02);
    EXPECT_EQ(p.getFriction(), 0.4);
}
