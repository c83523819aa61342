// The World's contract with a program that uses the library directly: a step refuses a dt it
// cannot take before moving anything, a swarm's reference survives the next swarm, and a const
// World may be read from two threads at once (a spring network's working memory is the caller's).
#include "pba/world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>
#include <vector>

#include "pba/forces.hpp"
#include "pba/particle.hpp"
#include "pba/scene/scene.hpp"
#include "pba/spring_network.hpp"

using namespace pba;

TEST(World, AStepRefusesADtThatIsNotFiniteAndPositiveBeforeMovingAnything)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0.0, -9.81, 0.0)));
    Particle ball;
    ball.setPos(dvec3(0.0, 2.0, 0.0));
    ball.setVel(dvec3(1.0, 0.0, 0.0));
    world.addParticle(ball);
    for (const double dt : {-1.0, 0.0, -0.0, std::numeric_limits<double>::quiet_NaN(),
                            std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
        try {
            world.step(dt);
            FAIL() << "took dt = " << dt;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("dt must be finite and positive"), std::string::npos) << e.what();
        }
        EXPECT_EQ(world.stepCount(), 0u);
        EXPECT_EQ(world.time(), 0.0);
        EXPECT_EQ(world.body(0).getPos(), dvec3(0.0, 2.0, 0.0));
        EXPECT_EQ(world.body(0).getVel(), dvec3(1.0, 0.0, 0.0));
    }
    world.step(0.01); // and a good one is still taken
    EXPECT_EQ(world.stepCount(), 1u);
}

TEST(World, ASwarmsReferenceStaysValidAsMoreSwarmsAreAdded)
{
    World world;
    world.setGround(0.0);
    SwarmDesc desc;
    desc.count = 4;
    desc.regionMin = dvec3(0.0, 1.0, 0.0);
    desc.regionMax = dvec3(1.0, 2.0, 1.0);
    desc.name = "first";
    Swarm& first = world.addSwarm(desc);
    for (int k = 0; k < 20; ++k) { // enough for any vector to have grown several times
        desc.name = "more" + std::to_string(k);
        world.addSwarm(desc);
    }
    EXPECT_EQ(&first, &world.swarm(0));
    EXPECT_EQ(first.name(), "first");
    first.set(0, Vec3<float>(0.5f, 3.0f, 0.5f), Vec3<float>(0.0f));
    EXPECT_EQ(world.swarm(0).position(0), Vec3<float>(0.5f, 3.0f, 0.5f));
    // A copy of the world has swarms of its own.
    World copy = world;
    copy.swarm(0).set(0, Vec3<float>(0.25f), Vec3<float>(0.0f));
    EXPECT_EQ(world.swarm(0).position(0), Vec3<float>(0.5f, 3.0f, 0.5f));
}

// World::acceleration is const; a cloth's springs are a SpringNetwork, whose first pass needs
// working memory. Two threads asking one const World for different bodies' accelerations at
// different trial states each get what one thread alone gets: the memory is each call's own.
TEST(World, TwoThreadsReadingOneConstWorldGetWhatOneThreadGets)
{
    const Scene scene = loadScene("cloth");
    const World& world = scene.world;
    ASSERT_GT(world.bodyCount(), 50u);
    const auto trial = [&](std::size_t i, int thread) {
        return world.body(i).getPos() + dvec3(0.01 * double(thread + 1), -0.02 * double(thread), 0.005);
    };
    const auto accelerations = [&](int thread) {
        std::vector<dvec3> a;
        for (int round = 0; round < 20; ++round)
            for (std::size_t i = 0; i < world.bodyCount(); ++i)
                a.push_back(world.acceleration(i, trial(i, thread), dvec3(0.1, 0.0, 0.0)));
        return a;
    };
    const std::vector<dvec3> alone0 = accelerations(0), alone1 = accelerations(1);
    std::vector<dvec3> together0, together1;
    std::thread other([&] { together1 = accelerations(1); });
    together0 = accelerations(0);
    other.join();
    EXPECT_EQ(together0, alone0);
    EXPECT_EQ(together1, alone1);
}

// The caller's scratch is where the network's first pass goes; without one it uses its own, and
// the forces are the same bit for bit.
TEST(SpringNetwork, WorksInTheCallersScratchOrItsOwnAlike)
{
    const Scene scene = loadScene("rope");
    const World& world = scene.world;
    const SpringNetwork* network = nullptr;
    for (std::size_t f = 0; f < world.forceCount(); ++f) {
        struct Find final : ForceVisitor {
            const SpringNetwork* found = nullptr;
            void visit(const SpringNetwork& n) override { found = &n; }
        } find;
        world.force(f).accept(find);
        network = find.found ? find.found : network;
    }
    ASSERT_NE(network, nullptr);
    std::vector<State> states;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        states.push_back(State{world.body(i).getPos() + dvec3(0.0, 0.01 * double(i % 3), 0.0), dvec3(0.0)});
    std::vector<ClonePtr<Body>> bodies;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        bodies.emplace_back(world.body(i).clone());
    const BodyStates in{bodies, states, {}, {}, {}};
    std::vector<dvec3> own(bodies.size(), dvec3(0.0)), kept(bodies.size(), dvec3(0.0)), scratch;
    Accumulators withoutScratch{own, {}};
    Accumulators withScratch{kept, {}, &scratch};
    network->accumulate(in, withoutScratch);
    network->accumulate(in, withScratch);
    EXPECT_EQ(scratch.size(), network->size());
    EXPECT_EQ(own, kept);
    EXPECT_NE(own[5], dvec3(0.0));
}

TEST(SpringNetwork, IsDampedWhenAnyOfItsSpringsIs)
{
    SpringNetwork::Link still{0, 1, 100.0, 1.0, 0.0}, damped{1, 2, 100.0, 1.0, 0.5};
    EXPECT_FALSE(SpringNetwork({still, still}).damped());
    EXPECT_TRUE(SpringNetwork({still, damped}).damped());
}

// Whether two balls collide is known from their step: asked of balls added since (or of a world
// never stepped) the answer is no, not a read past the last step's radii.
TEST(World, BallsAddedSinceTheLastStepDoNotYetCollide)
{
    World world;
    const auto addBall = [&](const dvec3& at) {
        auto ball = std::make_unique<Particle>();
        ball->setPos(at);
        ball->setRadius(0.1);
        world.addBody(std::move(ball));
    };
    addBall(dvec3(0.0));
    addBall(dvec3(1.0, 0.0, 0.0));
    EXPECT_FALSE(world.ballsCollide(0, 1));
    world.step(0.01);
    EXPECT_TRUE(world.ballsCollide(0, 1));
    addBall(dvec3(2.0, 0.0, 0.0));
    EXPECT_FALSE(world.ballsCollide(1, 2));
}
