// A swarm's Coulomb friction against the room: the rule its particles would have alone.
// Oracle: a puck sliding on a level floor decelerates at mu g, so it stops after v0^2 / (2 mu g).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "pba/forces.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

constexpr double kG = 9.81;

/// n pucks of radius r on the floor of a 4 m room, sliding at 1 m/s along x, under gravity.
World slidingSwarm(std::size_t n, double mu, CollisionResponse response, double radius = 0.05)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -kG, 0)));
    world.setRoom({dvec3(-2, 0, -2), dvec3(2, 4, 2)});
    world.setCollisionResponse(response);
    SwarmDesc desc;
    desc.name = "pucks";
    desc.count = n;
    desc.regionMin = dvec3(-1.9, radius, -1.9);
    desc.regionMax = dvec3(-1.0, radius, 1.9);
    desc.velocity = dvec3(1.0, 0.0, 0.0);
    desc.radius = radius;
    desc.friction = mu;
    desc.restitution = 0.0;
    world.addSwarm(desc);
    return world;
}

} // namespace

TEST(SwarmFriction, APuckSlidingOnTheFloorStopsAfterV0SquaredOverTwoMuG)
{
    const double mu = 0.5, expected = 1.0 / (2.0 * mu * kG);
    World world = slidingSwarm(1, mu, CollisionResponse::Exact);
    const double start = world.swarm(0).position(0).x;
    for (int step = 0; step < 500; ++step)
        world.step(1e-3);
    EXPECT_NEAR(world.swarm(0).position(0).x - start, expected, 0.01 * expected);
    EXPECT_EQ(world.swarm(0).velocity(0).x, 0.0f) << "it stopped";
}

TEST(SwarmFriction, WithoutFrictionThePucksKeepSliding)
{
    World world = slidingSwarm(600, 0.0, CollisionResponse::Reflect);
    for (int step = 0; step < 200; ++step)
        world.step(1e-3);
    for (std::size_t i = 0; i < world.swarm(0).size(); ++i)
        ASSERT_EQ(world.swarm(0).velocity(i).x, 1.0f) << "puck " << i;
}

// Every response: the swarm's pucks (blocks of them, all on the floor) follow double-precision
// Particles of the same friction, and come to rest where they do. Points: Particles with a
// radius would collide with each other, which a swarm's do only with "collide".
TEST(SwarmFriction, PucksFollowParticlesOfTheSameFriction)
{
    for (CollisionResponse response : {CollisionResponse::Reflect, CollisionResponse::Clamp,
                                       CollisionResponse::Exact}) {
        World world = slidingSwarm(600, 0.05, response, 0.0);
        const Swarm& swarm = world.swarm(0);
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            Particle p;
            p.setFriction(0.05);
            p.setCor(0.0);
            p.setPos(dvec3(swarm.position(i)));
            p.setVel(dvec3(swarm.velocity(i)));
            world.addParticle(p);
        }
        for (int step = 0; step < 1500; ++step)
            world.step(2e-3);
        double worst = 0.0, fastest = 0.0;
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            worst = std::max(worst, glm::length(dvec3(swarm.position(i)) - world.body(i).getPos()));
            const Vec3<float> v = swarm.velocity(i); // sliding: the reflect rule leaves a resting one g dt downward
            fastest = std::max(fastest, std::hypot(double(v.x), double(v.z)));
        }
        EXPECT_LT(worst, 1e-3) << collisionResponseName(response);
        EXPECT_LT(fastest, 1e-3) << collisionResponseName(response) << ": friction stopped them";
    }
}

TEST(SwarmFriction, ResultsDoNotDependOnTheThreadCount)
{
    for (CollisionResponse response : {CollisionResponse::Reflect, CollisionResponse::Exact}) {
        World one = slidingSwarm(40000, 0.2, response), two = slidingSwarm(40000, 0.2, response);
        one.setThreads(1);
        two.setThreads(2);
        for (int step = 0; step < 100; ++step) {
            one.step(2e-3);
            two.step(2e-3);
        }
        for (std::size_t i = 0; i < one.swarm(0).size(); ++i) {
            ASSERT_EQ(one.swarm(0).position(i), two.swarm(0).position(i)) << "particle " << i;
            ASSERT_EQ(one.swarm(0).velocity(i), two.swarm(0).velocity(i)) << "particle " << i;
        }
    }
}

// A puck rubs the same in a crowded block (the collision pass over the whole block), among a
// few gathered from several blocks, alone, and at a wall (the whole rule): 2048 pucks, three
// blocks sliding on the floor (every sixty-fourth into the low x wall) and one falling onto it,
// step for step the states of 2048 swarms of one.
TEST(SwarmFriction, APuckRubsAlikeInABlockInABatchAndAlone)
{
    for (CollisionResponse response : {CollisionResponse::Reflect, CollisionResponse::Clamp}) {
        World world = slidingSwarm(2048, 0.3, response, 0.0);
        Swarm& swarm = world.swarm(0);
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            const float u = float(i % 64) / 64.0f, w = float(i / 64) / 32.0f;
            const bool resting = i < 1536, atWall = resting && i % 64 == 0;
            const float across = atWall ? -1.998f + 0.0005f * float(i / 64) : -1.9f + 3.8f * u;
            swarm.set(i, Vec3<float>(across, resting ? 1e-4f : 0.01f + 0.05f * w, -1.9f + 3.8f * w),
                      Vec3<float>(atWall ? -0.5f : 0.6f * (u - 0.5f), resting ? -0.05f : -0.5f, 0.2f));
        }
        std::vector<World> alone;
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            alone.push_back(slidingSwarm(1, 0.3, response, 0.0));
            alone.back().swarm(0).set(0, swarm.position(i), swarm.velocity(i));
        }
        for (int step = 0; step < 60; ++step) {
            world.step(2e-3);
            for (std::size_t i = 0; i < swarm.size(); ++i) {
                alone[i].step(2e-3);
                ASSERT_EQ(swarm.position(i), alone[i].swarm(0).position(0)) << "puck " << i << " step " << step;
                ASSERT_EQ(swarm.velocity(i), alone[i].swarm(0).velocity(0)) << "puck " << i << " step " << step;
            }
        }
    }
}

// Colliding grains hold their slip on the floor as static friction (an anchor), but a grain that
// slides (kinetic friction) drags its anchor along, a hundredth of its width behind: it stops
// after v0^2 / (2 mu g), as a lone puck does, and stays where it stopped, pulled back by no more
// than that rather than towards where it landed.
TEST(SwarmFriction, ACollidingGrainSlidingOnTheFloorStopsWhereAPuckDoesAndStaysThere)
{
    const double mu = 0.5, expected = 1.0 / (2.0 * mu * kG);
    for (CollisionResponse response : {CollisionResponse::Reflect, CollisionResponse::Exact}) {
        World world = slidingSwarm(2, mu, response, 0.01);
        SwarmDesc desc = world.swarm(0).desc();
        desc.collide = true;
        Swarm& swarm = world.swarm(0) = Swarm(desc);
        swarm.set(0, Vec3<float>(-1.5f, 0.01f, -1.0f), Vec3<float>(1.0f, 0.0f, 0.0f));
        swarm.set(1, Vec3<float>(-1.5f, 0.01f, 1.0f), Vec3<float>(1.0f, 0.0f, 0.0f)); // far from it
        for (int step = 0; step < 250; ++step) // 0.5 s: stopped after 0.2
            world.step(2e-3);
        const float stopped = swarm.position(0).x;
        EXPECT_NEAR(stopped + 1.5, expected, 0.01 * expected) << collisionResponseName(response);
        for (int step = 0; step < 500; ++step)
            world.step(2e-3);
        EXPECT_NEAR(swarm.position(0).x, stopped, 2e-4) << collisionResponseName(response) << ": not pulled back";
        EXPECT_EQ(swarm.velocity(0).x, 0.0f) << collisionResponseName(response);
    }
}

// A grain resting in the hollow of two on the floor: each lower one is pushed outwards at
// tan 30 / 2 of a grain's weight and pressed on the floor by 3/2 of one, so Coulomb's static
// friction holds the three for mu above tan 30 / 3 = 0.192 and not below. With mu 0.25 every
// grain stays within 0.1 mm over 10 s; with mu 0.15 the lower two slide apart (the top one falls
// between). Measured, the rule holds them down to mu = 0.165: its passes over speeds and over
// positions are each bounded by mu times the push, which makes it about 15% stronger than Coulomb
// at the limit. (Before the contacts remembered their slip, the three slid apart at mu = 0.5.)
World hollowOfTwo(double mu)
{
    const float r = 0.01f;
    World world = slidingSwarm(3, mu, CollisionResponse::Reflect, r);
    SwarmDesc desc = world.swarm(0).desc();
    desc.collide = true;
    Swarm& swarm = world.swarm(0) = Swarm(desc);
    swarm.set(0, Vec3<float>(-r, r, 0.0f), Vec3<float>(0.0f));
    swarm.set(1, Vec3<float>(r, r, 0.0f), Vec3<float>(0.0f));
    swarm.set(2, Vec3<float>(0.0f, r + std::sqrt(3.0f) * r, 0.0f), Vec3<float>(0.0f));
    return world;
}

TEST(SwarmFriction, AGrainInTheHollowOfTwoOnTheFloorStaysPutAboveTheFrictionItNeeds)
{
    World world = hollowOfTwo(0.25);
    const std::vector<Vec3<float>> start{world.swarm(0).position(0), world.swarm(0).position(1),
                                         world.swarm(0).position(2)};
    for (int step = 0; step < 5000; ++step)
        world.step(2e-3);
    for (std::size_t i = 0; i < 3; ++i)
        EXPECT_LT(glm::length(world.swarm(0).position(i) - start[i]), 1e-4f) << "grain " << i;
    World slippery = hollowOfTwo(0.15);
    for (int step = 0; step < 500; ++step)
        slippery.step(2e-3);
    EXPECT_GT(slippery.swarm(0).position(1).x - slippery.swarm(0).position(0).x, 0.025f) << "spread apart";
}
