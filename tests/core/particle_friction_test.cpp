// Coulomb friction of particles against the room, and resting contact counted as contact.
// Oracles: a body sliding on a level floor decelerates at mu g, so it stops after
// v0^2 / (2 mu g); on a ramp of angle theta it stays while tan(theta) <= mu and otherwise slides
// down with a = g (sin(theta) - mu cos(theta)), covering a t^2 / 2.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "core/surfaces/collision_rules.hpp"
#include "pba/forces.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

constexpr double kG = 9.81;

World slidingWorld(CollisionResponse response, Integrator integrator, double mu, double restitution)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -kG, 0)));
    world.setRoom({dvec3(-4, 0, -4), dvec3(4, 4, 4)});
    world.setCollisionResponse(response);
    Particle puck;
    puck.setRadius(0.05);
    puck.setPos(dvec3(0.0, 0.05, 0.0));
    puck.setVel(dvec3(1.0, 0.0, 0.0));
    puck.setFriction(mu);
    puck.setCor(restitution);
    puck.setIntegrator(integrator);
    world.addParticle(puck);
    return world;
}

} // namespace

TEST(ParticleFriction, APuckSlidingOnTheFloorStopsAfterV0SquaredOverTwoMuG)
{
    const double mu = 0.5, expected = 1.0 / (2.0 * mu * kG);
    // The exact response rubs while the puck rests on the floor; xpbd (a system's step) keeps it
    // on the floor in each substep, cutting its move along it by mu times the depth it put it back.
    for (const Integrator integrator : {Integrator::SemiImplicitEuler, Integrator::Xpbd}) {
        World world = slidingWorld(CollisionResponse::Exact, integrator, mu, 0.0);
        for (int step = 0; step < 500; ++step)
            world.step(1e-3);
        const Body& puck = world.body(0);
        EXPECT_NEAR(puck.getPos().x, expected, 0.01 * expected) << integratorName(integrator);
        EXPECT_LT(std::hypot(puck.getVel().x, puck.getVel().z), 1e-12) << integratorName(integrator) << ": it stopped";
        EXPECT_NEAR(puck.getPos().y, 0.05, kG * 1e-6 * 1.01) << integratorName(integrator);
        EXPECT_EQ(world.bounceCount(0), 0u) << integratorName(integrator) << ": resting contact is not a bounce";
    }
}

TEST(ParticleFriction, WithoutFrictionThePuckKeepsSliding)
{
    World world = slidingWorld(CollisionResponse::Exact, Integrator::SemiImplicitEuler, 0.0, 0.0);
    for (int step = 0; step < 500; ++step)
        world.step(1e-3);
    EXPECT_DOUBLE_EQ(world.body(0).getVel().x, 1.0);
}

TEST(ParticleFriction, ARestingParticleUnderTheReflectRuleCountsNoBounces)
{
    // The rope end: lying on the floor, pushed back every step, it counted a bounce at
    // nearly every one. A drop first: that one impact is a bounce.
    for (const double restitution : {0.0, 0.5}) {
        World world = slidingWorld(CollisionResponse::Reflect, Integrator::Xpbd, 0.3, restitution);
        world.body(0).setPos(dvec3(0.0, 0.3, 0.0));
        for (int step = 0; step < 4000; ++step)
            world.step(1e-3);
        EXPECT_LE(world.bounceCount(0), 40u) << "e = " << restitution << ": a few real bounces, not one a step";
        EXPECT_LT(std::abs(world.body(0).getVel().x), 1e-9) << "friction stopped it";
    }
}

namespace {

/// A particle resting on a plane through the origin tilted by theta about z, under gravity, for
/// `steps` steps of dt with the exact rule; returns its displacement.
dvec3 onRamp(double theta, double mu, int steps, double dt)
{
    const std::array<Plane, 1> ramp{Plane{dvec3(-std::sin(theta), std::cos(theta), 0.0), 0.0}};
    dvec3 x(0.0), v(0.0);
    auto gravity = [](const dvec3&, const dvec3&) { return dvec3(0.0, -kG, 0.0); };
    for (int step = 0; step < steps; ++step)
        stepExact(Integrator::SemiImplicitEuler, std::span<const Plane>(ramp), 0.0, x, v, dt, gravity, mu);
    return x;
}

} // namespace

TEST(ParticleFriction, BelowTheFrictionAngleAParticleOnARampStays)
{
    const double theta = 20.0 * std::numbers::pi / 180.0; // tan = 0.364
    EXPECT_LT(glm::length(onRamp(theta, 0.4, 2000, 1e-3)), 1e-12);
    EXPECT_LT(glm::length(onRamp(theta, std::tan(theta) * 1.001, 2000, 1e-3)), 1e-12) << "just inside the cone";
}

TEST(ParticleFriction, AboveTheFrictionAngleItSlidesWithGSinMinusMuCos)
{
    const double theta = 30.0 * std::numbers::pi / 180.0, mu = 0.2, t = 1.0;
    const double a = kG * (std::sin(theta) - mu * std::cos(theta));
    const dvec3 x = onRamp(theta, mu, 1000, t / 1000);
    EXPECT_NEAR(glm::length(x), 0.5 * a * t * t, 0.01 * 0.5 * a * t * t);
    EXPECT_LT(x.x, 0.0) << "down the slope";
}
