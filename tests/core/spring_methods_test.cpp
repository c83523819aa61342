// The methods that step springs implicitly, against exact oracles: backward Euler's discrete
// recurrence on the harmonic oscillator (its damping, 1 / (1 + omega^2 dt^2) of the energy a step)
// and its order; XPBD's equality with backward Euler for one spring, its convergence to the
// springs' motion as the substeps grow, and to the stiff limit (a pendulum on a rod) as the
// compliance vanishes; both on a cloth, the same states on any number of threads.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include "pba/forces.hpp"
#include "pba/scene/scene.hpp"
#include "pba/spring_network.hpp"
#include "pba/swarm.hpp"
#include "pba/world.hpp"

#include "particle_systems/backward_euler.hpp"

using namespace pba;

namespace {

constexpr double kG = 9.81;

/// A 1 kg particle on an undamped anchored spring (k = omega^2), displaced s0 along it from rest
/// length L = 2: s(t) = s0 cos(omega t). No gravity, no surfaces.
World oscillator(Integrator integrator, double omega, double s0)
{
    World world;
    Particle p;
    p.setPos(dvec3(0.0, -2.0 - s0, 0.0));
    p.setIntegrator(integrator);
    world.addParticle(p);
    world.addForce(std::make_unique<Spring>(0, dvec3(0.0), omega * omega, 2.0, 0.0));
    return world;
}

/// The displacement along the spring (downwards positive).
double stretch(const World& world) { return -world.body(0).getPos().y - 2.0; }

/// The largest |s(t) - s0 cos(omega t)| over [0, T].
double oscillatorError(Integrator integrator, double dt, double T, int substeps = 1)
{
    const double omega = std::sqrt(10.0), s0 = 1.0;
    World world = oscillator(integrator, omega, s0);
    world.setXpbdSubsteps(substeps);
    double worst = 0.0;
    for (int n = 1; n <= int(std::lround(T / dt)); ++n) {
        world.step(dt);
        worst = std::max(worst, std::abs(stretch(world) - s0 * std::cos(omega * n * dt)));
    }
    return worst;
}

/// States of every body, for comparing runs to the bit.
std::vector<State> states(const World& world)
{
    std::vector<State> out;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        out.push_back(world.body(i).getState());
    return out;
}

bool sameBits(const std::vector<State>& a, const std::vector<State>& b)
{
    if (a.size() != b.size())
        return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].pos != b[i].pos || a[i].vel != b[i].vel)
            return false;
    return true;
}

} // namespace

// Backward Euler on s'' = -omega^2 s: s1 = s0 + dt v1, v1 = v0 - dt omega^2 s1, so
//     (s1, v1) = (s0 + dt v0, v0 - dt omega^2 s0) / (1 + omega^2 dt^2),
// a rotation in (omega s, v) scaled by 1 / sqrt(1 + omega^2 dt^2): the energy falls by exactly
// 1 / (1 + omega^2 dt^2) every step. Along its own axis the linearised spring is exact.
TEST(BackwardEuler, ABearersPreconditionerInvertsToRounding)
{
    // A body's mass and inertia with two held members' outer products: symmetric positive
    // definite, as every bearer's matrix is; its inverse times it is the identity.
    detail::BodyMass body{20.0, dmat3(dvec3(0.7, 0.1, -0.05), dvec3(0.1, 0.9, 0.2), dvec3(-0.05, 0.2, 1.3))};
    detail::Mat6 a(body);
    a.addOuter({dvec3(0, 1, 0), dvec3(0.3, 0, -0.4)}, 5e3);
    a.addOuter({dvec3(0.2, 1, 0), dvec3(-0.3, 0.1, 0.4)}, 2e3);
    const detail::Mat6 inverse = a.inverse();
    for (int c = 0; c < 6; ++c) {
        detail::Twist e;
        (c < 3 ? e.linear : e.angular)[c % 3] = 1.0;
        const detail::Twist back = a.times(inverse.times(e));
        EXPECT_NEAR(glm::length(back.linear - e.linear) + glm::length(back.angular - e.angular), 0.0, 1e-12) << c;
    }
}

TEST(BackwardEuler, FollowsItsDiscreteRecurrenceAndDampsByOnePlusOmegaDtSquared)
{
    const double omega = 30.0, dt = 0.01, s0 = 0.1;
    World world = oscillator(Integrator::ImplicitEuler, omega, s0);
    double s = s0, v = 0.0;
    const double e0 = world.totalEnergy();
    const double a = omega * omega * dt * dt;
    for (int n = 1; n <= 50; ++n) {
        world.step(dt);
        const double s1 = (s + dt * v) / (1.0 + a), v1 = (v - dt * omega * omega * s) / (1.0 + a);
        s = s1;
        v = v1;
        EXPECT_NEAR(stretch(world), s, 1e-14) << n;
        EXPECT_NEAR(-world.body(0).getVel().y, v, 1e-12) << n;
        EXPECT_NEAR(world.totalEnergy() / e0, std::pow(1.0 + a, -n), 1e-12) << n;
    }
}

// Stable at any dt: at omega dt = 200 (a hundred times semi-implicit Euler's limit, 2) the
// energy still only falls, step by step.
TEST(BackwardEuler, IsStableAtAHundredTimesTheExplicitLimit)
{
    const double omega = 30.0, dt = 200.0 / omega;
    World world = oscillator(Integrator::ImplicitEuler, omega, 0.1);
    double before = world.totalEnergy();
    for (int n = 0; n < 20; ++n) {
        world.step(dt);
        const double e = world.totalEnergy();
        EXPECT_LE(e, before) << n;
        before = e;
    }
}

// A spring turning fast: a 1 kg particle at rest length 1 from its anchor (k = 100, omega = 10)
// moving across it at 3 m/s, at dt = 1. Linearised once at the start, the spring is stiff only
// along its start direction, so the step carries the particle along the tangent to a stretch of
// sqrt(10) - 1 and the energy grows 50-fold. The force at the start is zero, so Newton's
// corrections run until the nonlinear step's equations, m (v1 - v0) = dt f(x0 + dt v1), hold to
// rounding (or for kMaxNewtonIterations); after it the energy only falls.
TEST(BackwardEuler, SolvesTheNonlinearStepOfASpringTurningFar)
{
    const double k = 100.0, dt = 1.0;
    World world;
    Particle p;
    p.setPos(dvec3(1.0, 0.0, 0.0));
    p.setVel(dvec3(0.0, 3.0, 0.0));
    p.setIntegrator(Integrator::ImplicitEuler);
    world.addParticle(p);
    world.addForce(std::make_unique<Spring>(0, dvec3(0.0), k, 1.0, 0.0));
    const double e0 = world.totalEnergy();
    world.step(dt);
    const State end = world.body(0).getState();
    EXPECT_NEAR(glm::length(end.pos - (dvec3(1.0, 0.0, 0.0) + dt * end.vel)), 0.0, 1e-12);
    const dvec3 force = -k * (glm::length(end.pos) - 1.0) * glm::normalize(end.pos);
    EXPECT_LE(glm::length((end.vel - dvec3(0.0, 3.0, 0.0)) - dt * force), 1e-6);
    double before = world.totalEnergy();
    EXPECT_LT(before, e0);
    for (int n = 0; n < 20; ++n) {
        world.step(dt);
        const double e = world.totalEnergy();
        EXPECT_LE(e, before) << n;
        before = e;
    }
}

// First order: halving dt halves the largest error over 2 s.
TEST(BackwardEuler, ConvergesAtOrderOne)
{
    const double coarse = oscillatorError(Integrator::ImplicitEuler, 0.002, 2.0);
    const double fine = oscillatorError(Integrator::ImplicitEuler, 0.001, 2.0);
    EXPECT_NEAR(std::log2(coarse / fine), 1.0, 0.05);
    EXPECT_EQ(integratorOrder(Integrator::ImplicitEuler), 1);
}

// With no spring, implicit in nothing: a falling particle moves as by semi-implicit Euler, to the bit.
TEST(BackwardEuler, WithoutASpringIsSemiImplicitEuler)
{
    auto fall = [](Integrator integrator) {
        World world;
        world.addForce(std::make_unique<Gravity>(dvec3(0.0, -kG, 0.0)));
        world.addForce(std::make_unique<Drag>(0.3));
        Particle p;
        p.setPos(dvec3(0.0, 10.0, 0.0));
        p.setVel(dvec3(1.0, 2.0, 0.5));
        p.setIntegrator(integrator);
        world.addParticle(p);
        for (int n = 0; n < 100; ++n)
            world.step(0.01);
        return states(world);
    };
    EXPECT_TRUE(sameBits(fall(Integrator::ImplicitEuler), fall(Integrator::SemiImplicitEuler)));
}

// One spring, one substep: XPBD's projection with compliance 1/k is backward Euler's step, so
// along the spring it follows the same recurrence (with the substep h = dt / substeps).
TEST(Xpbd, OneSpringIsBackwardEulerAtTheSubstep)
{
    const double omega = 30.0, dt = 0.02, s0 = 0.1;
    for (const int substeps : {1, 4}) {
        World xpbd = oscillator(Integrator::Xpbd, omega, s0);
        xpbd.setXpbdSubsteps(substeps);
        const double h = dt / substeps, a = omega * omega * h * h;
        double s = s0, v = 0.0;
        for (int n = 1; n <= 40; ++n) {
            xpbd.step(dt);
            for (int k = 0; k < substeps; ++k) {
                const double s1 = (s + h * v) / (1.0 + a), v1 = (v - h * omega * omega * s) / (1.0 + a);
                s = s1;
                v = v1;
            }
            EXPECT_NEAR(stretch(xpbd), s, 1e-13) << substeps << " substeps, step " << n;
        }
    }
}

// As the substeps grow, XPBD converges to the spring's exact motion at order one in the substep.
TEST(Xpbd, ConvergesToTheSpringsMotionAsTheSubstepsGrow)
{
    const double four = oscillatorError(Integrator::Xpbd, 0.01, 2.0, 4);
    const double eight = oscillatorError(Integrator::Xpbd, 0.01, 2.0, 8);
    const double sixteen = oscillatorError(Integrator::Xpbd, 0.01, 2.0, 16);
    EXPECT_NEAR(std::log2(four / eight), 1.0, 0.1);
    EXPECT_NEAR(std::log2(eight / sixteen), 1.0, 0.1);
}

// The stiff limit: a pendulum on a spring of stiffness 1e12 N/m (compliance 1e-12, a rod) under
// gravity. One constraint is solved exactly by one projection, so the rod keeps its length at
// any substep; as the substeps grow the swing's period converges to the rigid pendulum's,
// T = 4 sqrt(L / g) K(sin(theta0 / 2)), at order one.
TEST(Xpbd, ConvergesToTheRigidPendulumAsTheSubstepsGrow)
{
    const double length = 1.0, theta0 = 0.5;
    const double exact = 4.0 * std::sqrt(length / kG) * std::comp_ellint_1(std::sin(0.5 * theta0));
    auto periodError = [&](int substeps) {
        World world;
        world.addForce(std::make_unique<Gravity>(dvec3(0.0, -kG, 0.0)));
        Particle bob;
        bob.setPos(dvec3(length * std::sin(theta0), -length * std::cos(theta0), 0.0));
        bob.setIntegrator(Integrator::Xpbd);
        world.addParticle(bob);
        world.addForce(std::make_unique<Spring>(0, dvec3(0.0), 1e12, length, 0.0));
        world.setXpbdSubsteps(substeps);
        const double dt = 1.0 / 60.0;
        std::vector<double> crossings;
        double before = world.body(0).getPos().x;
        for (int n = 1; n <= 600; ++n) {
            world.step(dt);
            const double x = world.body(0).getPos().x;
            EXPECT_NEAR(glm::length(world.body(0).getPos()), length, 1e-9);
            if ((before > 0.0) != (x > 0.0))
                crossings.push_back(dt * (n - 1 + before / (before - x)));
            before = x;
        }
        return std::abs(2.0 * (crossings.back() - crossings.front()) / double(crossings.size() - 1) / exact - 1.0);
    };
    const double four = periodError(4), sixteen = periodError(16);
    EXPECT_NEAR(std::log2(four / sixteen), 2.0, 0.3); // a quarter of the error at four times the substeps
    EXPECT_LT(sixteen, 0.005);
}

// Many stiff constraints (a hanging chain of 20 rods, compliance 1e-12) are not solved exactly by
// one Gauss-Seidel pass: with one sweep a substep the chain stretched under its whip. With (w_a + w_b) k h^2 far above Xpbd::kStiff the substep sweeps until each rod's
// error is under Xpbd::kTolerance (1%) of its length, so the chain holds that at any substeps.
TEST(Xpbd, AChainOfRodsHoldsItsLengthAtAnySubsteps)
{
    auto worstStretch = [](int substeps) {
        World world;
        world.addForce(std::make_unique<Gravity>(dvec3(0.0, -kG, 0.0)));
        std::vector<SpringNetwork::Link> links;
        const int n = 20;
        const double link = 0.1;
        for (int k = 0; k <= n; ++k) {
            Particle p;
            p.setPos(dvec3(k * link, 0.0, 0.0)); // held out level, pinned at its first end
            p.setMass(0.05);
            p.setFixed(k == 0);
            p.setIntegrator(Integrator::Xpbd);
            world.addParticle(p);
            if (k > 0)
                links.push_back({std::size_t(k - 1), std::size_t(k), 1e12, link, 0.0});
        }
        world.addForce(std::make_unique<SpringNetwork>(links));
        world.setXpbdSubsteps(substeps);
        double worst = 0.0;
        for (int step = 0; step < 30; ++step) {
            world.step(1.0 / 60.0);
            for (int k = 1; k <= n; ++k)
                worst = std::max(worst, std::abs(glm::length(world.body(k).getPos() - world.body(k - 1).getPos()) / link - 1.0));
        }
        return worst;
    };
    for (int substeps : {1, 2, 8, 32})
        EXPECT_LT(worstStretch(substeps), 0.01) << substeps << " substeps";
}

// Both methods on a 24 x 24 cloth in the dryer: the same states to the bit on 1 thread and on
// all cores (each dot product is reduced over a fixed tree, each colour's constraints touch
// bodies of their own).
TEST(SpringMethods, GiveTheSameStatesOnAnyNumberOfThreads)
{
    // At a frame's dt, and at a quarter second, where backward Euler solves Newton's corrections
    // and xpbd sweeps a substep until its errors are small (stopping at the same sweep on any
    // number of threads: a sweep's largest error is a maximum, exact in any order).
    for (const auto& step : {std::pair{1.0 / 60.0, 20}, std::pair{0.25, 3}}) {
        const double dt = step.first; // not a structured binding: Clang 14 cannot capture one
        const int steps = step.second;
        for (const Integrator integrator : {Integrator::ImplicitEuler, Integrator::Xpbd}) {
            auto run = [&](int threads) {
                Scene scene = resizedClothInTheDryer(24);
                for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
                    scene.world.body(i).setIntegrator(integrator);
                scene.world.setThreads(threads);
                for (int n = 0; n < steps; ++n)
                    scene.world.step(dt);
                return states(scene.world);
            };
            EXPECT_TRUE(sameBits(run(1), run(0))) << integratorName(integrator) << " at dt " << dt;
            EXPECT_TRUE(sameBits(run(1), run(2))) << integratorName(integrator) << " at dt " << dt;
        }
    }
}

// They step particles joined by springs: a rigid body or a swarm given one is refused.
TEST(SpringMethods, AreRefusedForRigidBodiesAndSwarms)
{
    for (const Integrator integrator : {Integrator::ImplicitEuler, Integrator::Xpbd}) {
        World world;
        auto box = std::make_unique<RigidBody>();
        box->setName("box");
        box->setIntegrator(integrator);
        world.addBody(std::move(box));
        EXPECT_THROW(world.step(0.01), std::invalid_argument);
        SwarmDesc desc;
        desc.name = "rain";
        desc.count = 10;
        desc.integrator = integrator;
        EXPECT_THROW(World().addSwarm(desc), std::invalid_argument);
    }
    EXPECT_THROW(World().setXpbdSubsteps(0), std::invalid_argument);
}
