// Balls against balls. Oracles: a head-on elastic collision conserves momentum and energy, so
// two equal balls exchange velocities and unequal ones leave with
// v1' = ((m1 - m2) v1 + 2 m2 v2) / (m1 + m2); a ball resting on another resting on the floor has
// every force balanced and stays; the pairs are solved in index order, so the thread count
// changes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "pba/forces.hpp"
#include "pba/rigid_body.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

Particle ball(const dvec3& x, const dvec3& v, double mass, double radius, double cor = 1.0, double mu = 0.0)
{
    Particle p;
    p.setPos(x);
    p.setVel(v);
    p.setMass(mass);
    p.setRadius(radius);
    p.setCor(cor);
    p.setFriction(mu);
    return p;
}

} // namespace

TEST(ParticleContacts, TwoEqualBallsHeadOnExchangeVelocities)
{
    World world; // no gravity, no room: only the two balls
    world.addParticle(ball(dvec3(-1, 1, 0), dvec3(1, 0, 0), 0.5, 0.1));
    world.addParticle(ball(dvec3(1, 1, 0), dvec3(-1.5, 0, 0), 0.5, 0.1));
    for (int step = 0; step < 1000; ++step)
        world.step(1e-3);
    EXPECT_NEAR(glm::length(world.body(0).getVel() - dvec3(-1.5, 0, 0)), 0.0, 1e-9);
    EXPECT_NEAR(glm::length(world.body(1).getVel() - dvec3(1, 0, 0)), 0.0, 1e-9);
    EXPECT_GE(glm::length(world.body(1).getPos() - world.body(0).getPos()), 0.2 - 1e-12) << "apart again";
    // One impact, one bounce each, as a ball's off the floor is counted.
    EXPECT_EQ(world.bounceCount(0), 1u);
    EXPECT_EQ(world.bounceCount(1), 1u);
}

TEST(ParticleContacts, UnequalBallsHeadOnKeepMomentumAndEnergy)
{
    const double m1 = 1.0, m2 = 3.0, v1 = 2.0, v2 = -1.0;
    World world;
    world.addParticle(ball(dvec3(-1, 1, 0), dvec3(v1, 0, 0), m1, 0.1));
    world.addParticle(ball(dvec3(1, 1, 0), dvec3(v2, 0, 0), m2, 0.2));
    for (int step = 0; step < 1000; ++step)
        world.step(1e-3);
    EXPECT_NEAR(world.body(0).getVel().x, ((m1 - m2) * v1 + 2 * m2 * v2) / (m1 + m2), 1e-9);
    EXPECT_NEAR(world.body(1).getVel().x, ((m2 - m1) * v2 + 2 * m1 * v1) / (m1 + m2), 1e-9);
}

TEST(ParticleContacts, UnequalRestitutionsCombineAsTwoBodiesDo)
{
    // The larger restitution, as between rigid bodies (docs/scenes.md): a bouncy ball (e = 1)
    // meeting a dead one (e = 0) head-on rebounds elastically, and so would a bouncy die.
    World world;
    world.addParticle(ball(dvec3(-1, 1, 0), dvec3(1, 0, 0), 0.5, 0.1, 1.0));
    world.addParticle(ball(dvec3(1, 1, 0), dvec3(-1.5, 0, 0), 0.5, 0.1, 0.0));
    for (int step = 0; step < 1000; ++step)
        world.step(1e-3);
    EXPECT_NEAR(world.body(0).getVel().x, -1.5, 1e-9);
    EXPECT_NEAR(world.body(1).getVel().x, 1.0, 1e-9);
}

// Balls that would pass through each other within one step (4 cm balls closing at 10 m/s at
// dt 1/60 s) meet at their time of impact instead. With no gravity the paths are straight, so
// the oracle is exact: the balls touch at t* = (gap) / (closing speed), leave with the
// textbook's velocities, and are at their analytic places at the end.
TEST(ParticleContacts, BallsThatWouldPassInOneStepMeetAtTheirTimeOfImpact)
{
    const double m1 = 1.0, m2 = 3.0, v1 = 6.0, v2 = -4.0, r = 0.02, dt = 1.0 / 60.0;
    for (const double e : {1.0, 0.5}) {
        World world;
        world.addParticle(ball(dvec3(-0.5, 1, 0), dvec3(v1, 0, 0), m1, r, e));
        world.addParticle(ball(dvec3(0.5, 1, 0), dvec3(v2, 0, 0), m2, r, e));
        const int steps = 12; // 0.2 s; they meet at 0.096 s, inside the sixth step
        for (int step = 0; step < steps; ++step)
            world.step(dt);
        const double tImpact = (1.0 - 2.0 * r) / (v1 - v2), later = steps * dt - tImpact;
        const double u1 = (m1 * v1 + m2 * v2 - m2 * e * (v1 - v2)) / (m1 + m2);
        const double u2 = (m1 * v1 + m2 * v2 + m1 * e * (v1 - v2)) / (m1 + m2);
        EXPECT_NEAR(world.body(0).getVel().x, u1, 1e-12) << e;
        EXPECT_NEAR(world.body(1).getVel().x, u2, 1e-12) << e;
        EXPECT_NEAR(world.body(0).getPos().x, -0.5 + v1 * tImpact + u1 * later, 1e-12) << e;
        EXPECT_NEAR(world.body(1).getPos().x, 0.5 + v2 * tImpact + u2 * later, 1e-12) << e;
        EXPECT_EQ(world.bounceCount(0), 1u);
        EXPECT_EQ(world.bounceCount(1), 1u);
    }
}

TEST(ParticleContacts, AGlancingImpactWithinOneStepKeepsMomentumAndEnergy)
{
    // Equal balls, one at rest, hit at an impact parameter of half their reach: the normal at
    // impact is 30 degrees from the line of motion; frictionless and elastic, the struck ball
    // leaves along it at v cos 30 and the striker at right angles to it at v sin 30.
    const double r = 0.02, v = 12.0, dt = 1.0 / 60.0;
    World world;
    world.addParticle(ball(dvec3(-0.3, 1, 0), dvec3(v, 0, 0), 1.0, r));
    world.addParticle(ball(dvec3(0, 1 + r, 0), dvec3(0.0), 1.0, r));
    for (int step = 0; step < 4; ++step)
        world.step(dt);
    const dvec3 n(std::sqrt(3.0) / 2.0, 0.5, 0.0);
    const dvec3 struck = v * n.x * n, striker = dvec3(v, 0, 0) - struck;
    EXPECT_NEAR(glm::length(world.body(1).getVel() - struck), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(world.body(0).getVel() - striker), 0.0, 1e-12);
    const dvec3 momentum = world.body(0).getVel() + world.body(1).getVel();
    EXPECT_NEAR(glm::length(momentum - dvec3(v, 0, 0)), 0.0, 1e-12);
    const double energy = glm::dot(world.body(0).getVel(), world.body(0).getVel()) +
                          glm::dot(world.body(1).getVel(), world.body(1).getVel());
    EXPECT_NEAR(energy, v * v, 1e-10);
}

TEST(ParticleContacts, ABallKnockedIntoAThirdWithinTheStepMeetsItToo)
{
    // Three equal elastic 2 cm balls in a line, no gravity, the first at 12 m/s: at dt 1/60 s it
    // meets the second 0.8 of the way into the first step, which meets the third at 0.95. Each
    // stops where it struck, and the third goes on at 12 m/s from where it was struck.
    World world;
    world.addParticle(ball(dvec3(-0.2, 1, 0), dvec3(12, 0, 0), 1.0, 0.02));
    world.addParticle(ball(dvec3(0, 1, 0), dvec3(0.0), 1.0, 0.02));
    world.addParticle(ball(dvec3(0.07, 1, 0), dvec3(0.0), 1.0, 0.02));
    const double dt = 1.0 / 60.0;
    for (int step = 0; step < 2; ++step)
        world.step(dt);
    EXPECT_NEAR(glm::length(world.body(0).getVel()), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(world.body(1).getVel()), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(world.body(2).getVel() - dvec3(12, 0, 0)), 0.0, 1e-12);
    EXPECT_NEAR(world.body(0).getPos().x, -0.04, 1e-12);
    EXPECT_NEAR(world.body(1).getPos().x, 0.03, 1e-12);
    EXPECT_NEAR(world.body(2).getPos().x, 0.07 + 12.0 * (2.0 * dt - (0.16 + 0.03) / 12.0), 1e-12);
}

TEST(ParticleContacts, ABallThrownThroughAFixedBallInOneStepRebounds)
{
    World world;
    Particle post = ball(dvec3(0, 1, 0), dvec3(0.0), 1.0, 0.03, 0.5);
    post.setFixed(true);
    world.addParticle(post);
    world.addParticle(ball(dvec3(-0.4, 1, 0), dvec3(15, 0, 0), 0.2, 0.02, 0.5));
    for (int step = 0; step < 3; ++step)
        world.step(1.0 / 60.0);
    EXPECT_NEAR(world.body(1).getVel().x, -7.5, 1e-12) << "back at e times its speed";
    EXPECT_LT(world.body(1).getPos().x, -0.05);
}

TEST(ParticleContacts, APitOfBallsThrownAtALargeDtNeverGainsEnergyNorEndsAStepDeepInAnother)
{
    // 300 balls of 2-5 cm thrown at up to 10 m/s into a 2 m room at dt 1/60 s: many pairs meet
    // within a step, some of them beside a ball whose path the floor bent in that step. An
    // impulse from a path rather than from the velocities could push apart a pair already parting.
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
    world.setRoom({dvec3(-1, 0, -1), dvec3(1, 4, 1)});
    std::vector<dvec3> placed;
    for (int i = 0; placed.size() < 300; ++i) {
        const dvec3 at(0.9 * std::sin(1.3 * i), 1.8 + 1.6 * std::sin(0.7 * i + 1.0), 0.9 * std::cos(2.1 * i));
        if (std::any_of(placed.begin(), placed.end(), [&](const dvec3& p) { return glm::length(p - at) < 0.11; }))
            continue;
        placed.push_back(at);
        const dvec3 v(6 * std::sin(3.1 * i), 6 * std::cos(1.9 * i), 6 * std::sin(2.7 * i + 0.5));
        world.addParticle(ball(at, v, 0.05 + 0.45 * (0.5 + 0.5 * std::sin(5.3 * i)), 0.02 + 0.03 * (i % 7) / 6.0, 0.7, 0.4));
    }
    const auto energy = [&] {
        double e = 0.0;
        for (std::size_t i = 0; i < world.bodyCount(); ++i) {
            const Body& b = world.body(i);
            e += b.getMass() * (0.5 * glm::dot(b.getVel(), b.getVel()) + 9.81 * b.getPos().y);
        }
        return e;
    };
    double last = energy(), rose = 0.0, deepest = 0.0;
    for (int step = 0; step < 480; ++step) {
        world.step(1.0 / 60.0);
        const double now = energy();
        rose = std::max(rose, now - last);
        last = now;
        for (std::size_t i = 0; i < world.bodyCount(); ++i)
            for (std::size_t j = i + 1; j < world.bodyCount(); ++j) {
                const auto& a = static_cast<const Particle&>(world.body(i));
                const auto& b = static_cast<const Particle&>(world.body(j));
                const double overlap = a.getRadius() + b.getRadius() - glm::length(b.getPos() - a.getPos());
                deepest = std::max(deepest, overlap / (2.0 * std::min(a.getRadius(), b.getRadius())));
            }
    }
    EXPECT_LT(rose, 1e-9) << "J in one step";
    // Pairs that meet within a step no longer end it deep in each other (52% of the smaller
    // ball's diameter when only the sweeps looked, 13% with one impact a ball a step; what is
    // left is a ball knocked into one it was already touching, the sweeps' pair).
    EXPECT_LT(deepest, 0.15);
}

TEST(ParticleContacts, ABallRestingOnABallRestingOnTheFloorStaysPut)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
    world.setRoom({dvec3(-2, 0, -2), dvec3(2, 4, 2)});
    world.addParticle(ball(dvec3(0, 0.1, 0), dvec3(0.0), 1.0, 0.1, 0.5, 0.3));
    world.addParticle(ball(dvec3(0, 0.3, 0), dvec3(0.0), 1.0, 0.1, 0.5, 0.3));
    for (int step = 0; step < 10000; ++step) // 10 s
        world.step(1e-3);
    EXPECT_LT(glm::length(world.body(0).getPos() - dvec3(0, 0.1, 0)), 1e-4);
    EXPECT_LT(glm::length(world.body(1).getPos() - dvec3(0, 0.3, 0)), 1e-4);
    EXPECT_EQ(world.bounceCount(1), 0u) << "resting contact is no bounce";
}

TEST(ParticleContacts, ABallOnAFixedBallStaysBelowTheFrictionAngleAndSlidesAbove)
{
    // A ball that cannot roll, on a fixed ball with the normal at theta from straight up: static
    // friction holds it while tan theta < mu (0.6: 31 degrees), and it slides off above.
    auto drift = [](double degrees, double seconds) {
        World world;
        world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
        Particle below = ball(dvec3(0, 1, 0), dvec3(0.0), 1.0, 0.1, 0.0, 0.6);
        below.setFixed(true);
        world.addParticle(below);
        const double theta = degrees * 3.14159265358979323846 / 180.0;
        const dvec3 start = dvec3(0, 1, 0) + 0.2 * dvec3(std::sin(theta), std::cos(theta), 0);
        world.addParticle(ball(start, dvec3(0.0), 1.0, 0.1, 0.0, 0.6));
        for (int step = 0; step < int(seconds * 1000); ++step)
            world.step(1e-3);
        return glm::length(world.body(1).getPos() - start);
    };
    EXPECT_LT(drift(20.0, 5.0), 1e-4);
    EXPECT_GT(drift(45.0, 1.0), 0.05);
}

TEST(ParticleContacts, ResultsAreTheSameOnOneAndTwoThreads)
{
    // More balls than a task's grain, so two threads do split the grid's search; and again thrown
    // eight times as fast at dt 1/60 s, where many pairs meet within a step (their impacts).
    auto run = [](int threads, double speed, double dt) {
        World world;
        world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
        world.setRoom({dvec3(-1, 0, -1), dvec3(1, 2, 1)});
        world.setThreads(threads);
        for (int i = 0; i < 2100; ++i) {
            const dvec3 at(-0.95 + 0.04 * (i % 48), 0.05 + 0.04 * (i / 2304), -0.95 + 0.04 * ((i / 48) % 48));
            const dvec3 v = speed * dvec3(std::sin(1.7 * i), std::cos(2.3 * i), std::sin(0.9 * i));
            world.addParticle(ball(at, v, 1.0 + 0.1 * (i % 3), 0.015 + 0.002 * (i % 4), 0.6, 0.4));
        }
        for (int step = 0; step < 10; ++step)
            world.step(dt);
        std::vector<State> states;
        for (std::size_t i = 0; i < world.bodyCount(); ++i)
            states.push_back(world.body(i).getState());
        return states;
    };
    for (const auto& [speed, dt] : {std::pair(1.0, 2e-3), std::pair(8.0, 1.0 / 60.0)}) {
        const auto one = run(1, speed, dt), two = run(2, speed, dt);
        for (std::size_t i = 0; i < one.size(); ++i) {
            ASSERT_EQ(one[i].pos, two[i].pos) << i << " at " << speed;
            ASSERT_EQ(one[i].vel, two[i].vel) << i << " at " << speed;
        }
    }
}

namespace {

/// A swarm of colliding grains poured onto the floor of a small room, after `steps` steps.
World grainPile(int threads, int steps)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
    world.setRoom({dvec3(-0.5, 0, -0.5), dvec3(0.5, 2, 0.5)});
    world.setCollisionResponse(CollisionResponse::Reflect);
    world.setThreads(threads);
    SwarmDesc desc;
    desc.name = "grains";
    desc.count = 300;
    desc.regionMin = dvec3(-0.3, 0.3, -0.3);
    desc.regionMax = dvec3(0.3, 1.2, 0.3);
    desc.restitution = 0.2;
    desc.radius = 0.04;
    desc.friction = 0.5;
    desc.collide = true;
    desc.seed = 3;
    world.addSwarm(desc);
    for (int step = 0; step < steps; ++step)
        world.step(2e-3);
    return world;
}

} // namespace

TEST(ParticleContacts, ASwarmsGrainsPileUpWithoutOverlappingByMoreThanATenthOfTheirRadius)
{
    const World world = grainPile(0, 1500); // 3 s: poured, fallen and settled
    const Swarm& grains = world.swarm(0);
    const float r = grains.radius();
    float deepest = 0.0f, highest = 0.0f;
    for (std::size_t i = 0; i < grains.size(); ++i) {
        highest = std::max(highest, grains.position(i).y);
        ASSERT_GE(grains.position(i).y, r * 0.999f) << "on or above the floor";
        for (std::size_t j = i + 1; j < grains.size(); ++j)
            deepest = std::max(deepest, 2.0f * r - glm::length(grains.position(j) - grains.position(i)));
    }
    EXPECT_LT(deepest, 0.1f * r);
    EXPECT_GT(highest, 2.0f * r) << "they stack: 300 grains do not fit in one layer of the room";
}

TEST(ParticleContacts, ASwarmsGrainsAreTheSameOnOneAndTwoThreads)
{
    const World one = grainPile(1, 200), two = grainPile(2, 200);
    for (std::size_t i = 0; i < one.swarm(0).size(); ++i) {
        ASSERT_EQ(one.swarm(0).position(i), two.swarm(0).position(i)) << i;
        ASSERT_EQ(one.swarm(0).velocity(i), two.swarm(0).velocity(i)) << i;
    }
}

// The room is the world's boundary for balls too: a ball met the room by its own rule before
// the rigid bodies' contacts, and a heavy box driven into it against a wall must not leave it
// beyond the wall when the step ends.
TEST(ParticleContacts, ABallSqueezedAgainstAWallByAHeavyBodyStaysInTheRoom)
{
    for (const double speed : {10.0, 30.0, 60.0}) {
        World world;
        world.setRoom({dvec3(-2, 0, -2), dvec3(2, 4, 2)});
        const double r = 0.03;
        Particle& b = world.addParticle(ball(dvec3(1.95, 1.0, 0.0), dvec3(0.0), 0.05, r, 0.0, 0.1));
        auto box = std::make_unique<RigidBody>(Shape::box(dvec3(0.4)), 1000.0 / 0.064);
        box->setPos(dvec3(1.0, 1.0, 0.0));
        box->setVel(dvec3(speed, 0.0, 0.0));
        world.addBody(std::move(box));
        for (int n = 0; n < 100; ++n) {
            world.step(0.002);
            ASSERT_LE(b.getPos().x, 2.0 - r + 1e-9) << "at " << speed << " m/s, step " << n;
        }
    }
}
