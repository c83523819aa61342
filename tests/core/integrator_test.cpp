// The integrators against exact oracles: the closed-form discrete recurrences of free
// fall, the energy growth of forward Euler on the harmonic oscillator, and the measured
// orders of convergence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "pba/forces.hpp"
#include "pba/scene/scene.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

constexpr double kG = 9.81;

World freeFallWorld(Integrator integrator, double y0)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -kG, 0)));
    Particle p;
    p.setPos(dvec3(0, y0, 0));
    p.setIntegrator(integrator);
    world.addParticle(p);
    return world;
}

/// The spring scene: y(t) = 3 - cos(w t), w = sqrt(10), energy 0.5 v^2 + 0.5 w^2 (y - 3)^2.
World springWorld(Integrator integrator)
{
    World world = loadScene("spring").world;
    world.body(0).setIntegrator(integrator);
    return world;
}

/// Largest position error over [0, T]: unlike the error at one instant, it cannot pass
/// through zero by accident, so its ratio across dt measures the order reliably.
double springError(Integrator integrator, double dt, double T)
{
    World world = springWorld(integrator);
    const auto steps = static_cast<int>(std::lround(T / dt));
    double worst = 0.0;
    for (int n = 1; n <= steps; ++n) {
        world.step(dt);
        const double exact = 3.0 - std::cos(std::sqrt(10.0) * n * dt);
        worst = std::max(worst, std::abs(world.body(0).getPos().y - exact));
    }
    return worst;
}

} // namespace

TEST(Integrators, NamesRoundTrip)
{
    for (Integrator integrator : kAllIntegrators)
        EXPECT_EQ(integratorFromName(integratorName(integrator)), integrator);
    EXPECT_FALSE(integratorFromName("euler").has_value());
}

// Under constant gravity both Euler variants update v exactly (v_n = -g n dt); they
// differ in which velocity moves the position: forward Euler uses v_{k}, so
// y_n = y0 - g dt^2 (0 + 1 + ... + n-1) = y0 - g dt^2 n(n-1)/2; semi-implicit uses
// v_{k+1}, so y_n = y0 - g dt^2 n(n+1)/2.
TEST(Integrators, StageWeightsAreEachMethodsOwn)
{
    // v(t+dt) - v(t) = dt sum_k w_k a_k over the method's own evaluations, for a force that
    // depends on position and velocity (what the blow-up watch books a source's work by).
    for (const Integrator method : kEveryIntegrator) {
        dvec3 x(0.3, -0.2, 1.0), v(1.0, 0.5, -2.0);
        const dvec3 v0 = v;
        const std::span<const double> w = stageWeights(method);
        dvec3 weighted(0.0);
        std::size_t calls = 0;
        integrate(method, x, v, 0.05, [&](const dvec3& px, const dvec3& pv) {
            const dvec3 a = dvec3(std::sin(3.0 * px.y), px.x * pv.z, -pv.x * pv.x) - 4.0 * px;
            EXPECT_LT(calls, w.size()) << integratorName(method);
            weighted += w[std::min(calls++, w.size() - 1)] * a;
            return a;
        });
        EXPECT_EQ(calls, w.size()) << integratorName(method);
        EXPECT_NEAR(glm::length(v - v0 - 0.05 * weighted), 0.0, 1e-15) << integratorName(method);
    }
}

TEST(Integrators, EulerVariantsFollowTheirDiscreteFreeFallRecurrences)
{
    for (double dt : {0.0005, 0.01, 0.1}) {
        World fe = freeFallWorld(Integrator::ForwardEuler, 100.0);
        World sie = freeFallWorld(Integrator::SemiImplicitEuler, 100.0);
        for (int n = 1; n <= 200; ++n) {
            fe.step(dt);
            sie.step(dt);
            const double dn = n;
            EXPECT_NEAR(fe.body(0).getVel().y, -kG * dn * dt, 1e-12 * (1 + dn));
            EXPECT_NEAR(sie.body(0).getVel().y, -kG * dn * dt, 1e-12 * (1 + dn));
            EXPECT_NEAR(fe.body(0).getPos().y, 100.0 - kG * dt * dt * dn * (dn - 1) / 2, 1e-10 * (1 + dn * dn));
            EXPECT_NEAR(sie.body(0).getPos().y, 100.0 - kG * dt * dt * dn * (dn + 1) / 2, 1e-10 * (1 + dn * dn));
        }
    }
}

TEST(Integrators, VerletAndRK4AreExactForConstantAcceleration)
{
    for (Integrator integrator : {Integrator::VelocityVerlet, Integrator::RK4}) {
        for (double dt : {0.001, 0.1}) {
            World world = freeFallWorld(integrator, 100.0);
            world.body(0).setVel(dvec3(1.0, 4.0, -2.0));
            for (int n = 1; n <= 100; ++n) {
                world.step(dt);
                const double t = n * dt;
                const dvec3 x = world.body(0).getPos();
                EXPECT_NEAR(x.y, 100.0 + 4.0 * t - 0.5 * kG * t * t, 1e-11 * (1 + t * t)) << integratorName(integrator);
                EXPECT_NEAR(x.x, t, 1e-12 * (1 + t));
                EXPECT_NEAR(world.body(0).getVel().y, 4.0 - kG * t, 1e-12 * (1 + t));
            }
        }
    }
}

// Forward Euler on x'' = -w^2 x: (x, v) -> (x + v dt, v - w^2 x dt), so
// E' = 1/2 (v - w^2 x dt)^2 + 1/2 w^2 (x + v dt)^2 = (1 + w^2 dt^2) E, exactly.
TEST(Integrators, ForwardEulerOscillatorEnergyGrowsByOnePlusW2Dt2PerStep)
{
    const double w2 = 10.0;
    for (double dt : {0.001, 0.01, 0.05}) {
        World world = springWorld(Integrator::ForwardEuler);
        double previous = world.energy(0);
        for (int n = 0; n < 40; ++n) { // few enough steps that the bob never nears the anchor
            world.step(dt);
            const double now = world.energy(0);
            EXPECT_NEAR(now / previous, 1.0 + w2 * dt * dt, 1e-12);
            previous = now;
        }
    }
}

// Semi-implicit Euler conserves the modified energy 1/2 v^2 + 1/2 w^2 x^2 - 1/2 w^2 dt x v
// exactly, so the true energy stays within a band of relative width about w dt.
TEST(Integrators, SemiImplicitEulerOscillatorEnergyStaysBounded)
{
    for (double dt : {0.001, 0.01, 0.05}) {
        World world = springWorld(Integrator::SemiImplicitEuler);
        const double e0 = world.energy(0);
        const double band = std::sqrt(10.0) * dt;
        for (int n = 0; n < static_cast<int>(100.0 / dt); ++n) {
            world.step(dt);
            ASSERT_LT(std::abs(world.energy(0) / e0 - 1.0), band) << "dt " << dt << " step " << n;
        }
    }
}

// Global error ~ C dt^p: the slope of log(error) against log(dt) measures p. The dt range
// keeps every method in its asymptotic regime and RK4 above rounding.
TEST(Integrators, MeasuredConvergenceOrdersAre1124)
{
    const double T = 2.0;
    for (Integrator integrator : kAllIntegrators) {
        const double coarse = integrator == Integrator::RK4 ? 0.04 : 0.002;
        const double fine = coarse / 4;
        const double order =
            std::log(springError(integrator, coarse, T) / springError(integrator, fine, T)) / std::log(4.0);
        EXPECT_NEAR(order, integratorOrder(integrator), 0.3) << integratorName(integrator);
    }
}

TEST(Integrators, FixedParticleReceivesNoForceAndNeverMoves)
{
    World world = loadScene("integrators").world;
    const dvec3 start = world.body(0).getPos();
    ASSERT_TRUE(world.body(0).isFixed());
    for (int n = 0; n < 500; ++n)
        world.step(0.01);
    EXPECT_EQ(world.body(0).getPos(), start);
    EXPECT_EQ(world.body(0).getVel(), dvec3(0.0));
    EXPECT_EQ(world.acceleration(0, start, dvec3(0.0)), dvec3(0.0));
}

// RK4 must evaluate the forces at its intermediate states: with drag (a force that depends
// on velocity) it stays fourth order; reusing the start-of-step force would make it first order.
TEST(Integrators, MultiStageMethodsEvaluateForcesAtIntermediateStates)
{
    auto error = [](double dt) {
        World world;
        world.addForce(std::make_unique<Drag>(2.0));
        Particle p;
        p.setVel(dvec3(1.0, 0, 0));
        p.setIntegrator(Integrator::RK4);
        world.addParticle(p);
        for (int n = 0; n < static_cast<int>(std::lround(1.0 / dt)); ++n)
            world.step(dt);
        return std::abs(world.body(0).getVel().x - std::exp(-2.0));
    };
    EXPECT_NEAR(std::log(error(0.02) / error(0.005)) / std::log(4.0), 4.0, 0.3);
}
