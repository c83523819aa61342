// A ball in the dryer's air (`air_density`): quadratic drag on its cross-section relative to the
// air's velocity, and the pull of the air it displaces, against their definitions; a point in the
// same air feels the strength's push as before; a real ping-pong ball is caught and hovers where
// the air's speed holds its weight, as a particle and as a swarm's grain alike.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "pba/blow_dryer.hpp"
#include "pba/forces.hpp"
#include "pba/particle.hpp"
#include "pba/swarm.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRho = 1.2, kCd = 0.47; // air, a smooth sphere

/// A hair dryer blowing up from the floor.
BlowDryerField hairDryer(Falloff radial = Falloff::Smooth, FlowDirection direction = FlowDirection::Vertical)
{
    BlowDryerField f;
    f.height = 1.0;
    f.nozzleRadius = 0.025;
    f.topRadius = 0.3;
    f.strength = 0.05;
    f.radialFalloff = radial;
    f.direction = direction;
    f.airSpeed = 12.0;
    f.airDensity = kRho;
    f.dragCoefficient = kCd;
    return f;
}

/// (1/2) rho C_d pi r^2: the ball's drag over |u - v| (u - v).
double dragFactor(double r) { return 0.5 * kRho * kCd * kPi * r * r; }

} // namespace

TEST(BallInAir, ABallFeelsTheAirOnItsCrossSection)
{
    const BlowDryerField f = hairDryer();
    for (const double r : {0.01, 0.02, 0.05})
        for (const double h : {0.1, 0.4, 0.8})
            for (const dvec3 v : {dvec3(0.0), dvec3(0.3, -2.0, 0.1), dvec3(0.0, 15.0, 0.0)}) {
                const dvec3 x(0.0, h, 0.0); // on the axis: no pull
                const dvec3 relative = blowDryerAirVelocity(f, x) - v;
                const dvec3 expected = dragFactor(r) * glm::length(relative) * relative;
                const dvec3 F = blowDryerForce(f, x, v, r);
                EXPECT_NEAR(glm::length(F - expected), 0.0, 1e-12 * glm::length(expected)) << r << " " << h;
            }
}

// Off the axis, what is left after the drag is (beta / 2) grad_perp |u|^2 with beta = rho V.
TEST(BallInAir, ABallIsPulledTowardTheAxisByTheAirItDisplaces)
{
    for (const Falloff radial : {Falloff::Linear, Falloff::Quadratic, Falloff::Smooth})
        for (const FlowDirection direction : {FlowDirection::Vertical, FlowDirection::ConeFlow}) {
            const BlowDryerField f = hairDryer(radial, direction);
            const double r = 0.02, beta = kRho * 4.0 / 3.0 * kPi * r * r * r;
            for (const double h : {0.2, 0.5})
                for (const double off : {0.01, 0.04}) {
                    const dvec3 dir(0.6, 0.0, 0.8), x = dvec3(0, h, 0) + off * dir;
                    auto speed2 = [&](double rr) {
                        const dvec3 u = blowDryerAirVelocity(f, dvec3(0, h, 0) + rr * dir);
                        return glm::dot(u, u);
                    };
                    const double e = 1e-7;
                    const double gradient = (speed2(off + e) - speed2(off - e)) / (2 * e);
                    const dvec3 u = blowDryerAirVelocity(f, x);
                    const dvec3 pull = blowDryerForce(f, x, dvec3(0.0), r) - dragFactor(r) * glm::length(u) * u;
                    EXPECT_NEAR(glm::dot(pull, dir), 0.5 * beta * gradient, 1e-6 * std::abs(beta * gradient))
                        << falloffName(radial) << " h " << h << " off " << off;
                    EXPECT_LT(glm::dot(pull, dir), 0.0) << "toward the axis";
                }
        }
}

TEST(BallInAir, APointInTheSameAirFeelsTheStrengthsPushAsBefore)
{
    BlowDryerField withoutDensity = hairDryer();
    withoutDensity.airDensity = 0.0;
    for (const dvec3 x : {dvec3(0, 0.3, 0), dvec3(0.05, 0.5, -0.02), dvec3(0.01, -0.02, 0.0)}) {
        const dvec3 v(0.2, -1.0, 0.3);
        const dvec3 point = blowDryerForce(hairDryer(), x, v, 0.0);
        EXPECT_EQ(point, blowDryerForce(withoutDensity, x, v, 0.0));
        EXPECT_EQ(point, blowDryerForce(withoutDensity, x, v, 0.02)) << "without a density size does not matter";
    }
}

TEST(BallInAir, OutsideTheJetAMovingBallFeelsNoAir)
{
    // The room's still air is the `drag` force's business, not the dryer's.
    for (const dvec3 x : {dvec3(0.5, 0.3, 0.0), dvec3(0.0, 1.5, 0.0), dvec3(0.2, 0.05, 0.0)})
        EXPECT_EQ(blowDryerForce(hairDryer(), x, dvec3(1.0, -3.0, 2.0), 0.02), dvec3(0.0));
}

// The World's two paths to a body's force, one body at a time (an independent particle) and all
// at once (a coupled system's or a rigid world's), ask the particle for its radius alike.
TEST(BallInAir, EveryPathOfTheForceUsesTheParticlesRadius)
{
    const BlowDryer dryer(hairDryer());
    std::vector<ClonePtr<Body>> bodies;
    for (const double r : {0.0, 0.02}) {
        auto p = std::make_unique<Particle>();
        p->setRadius(r);
        bodies.emplace_back(std::move(p));
    }
    const std::vector<State> states{{dvec3(0.01, 0.3, 0), dvec3(0, -1, 0)}, {dvec3(0.01, 0.3, 0), dvec3(0, -1, 0)}};
    std::vector<dvec3> forces(2, dvec3(0.0));
    Accumulators out{forces, {}};
    dryer.accumulate(BodyStates{bodies, states, {}, {}, {}}, out);
    for (std::size_t i = 0; i < 2; ++i)
        EXPECT_EQ(forces[i], dryer.force(i, *bodies[i], states[i].pos, states[i].vel)) << i;
    EXPECT_NE(forces[0], forces[1]);
}

// The ping-pong ball: 2.7 g, 40 mm. It hovers where (1/2) rho C_d pi r^2 |u|^2 = m g, on the axis
// at h = H (1 - |u| / U) for the linear axial falloff: 0.2796 m. Let go above the jet and off its
// axis, it is caught, bobs and settles there, as a particle and as a swarm's grain.
TEST(BallInAir, APingPongBallIsCaughtAndHoversWhereTheAirHoldsItsWeight)
{
    const double m = 0.0027, r = 0.02, g = 9.81;
    const BlowDryerField f = hairDryer();
    const double hover = f.height * (1.0 - std::sqrt(m * g / dragFactor(r)) / f.airSpeed);
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -g, 0)));
    world.addForce(std::make_unique<BlowDryer>(f));
    world.setRoom({dvec3(-1, 0, -1), dvec3(1, 2, 1)});
    auto ball = std::make_unique<Particle>();
    ball->setMass(m);
    ball->setRadius(r);
    ball->setPos(dvec3(0.01, 0.6, 0.0));
    world.addBody(std::move(ball));
    SwarmDesc grain;
    grain.name = "grain";
    grain.count = 1;
    grain.regionMin = grain.regionMax = dvec3(0.0, 0.6, 0.01);
    grain.mass = m;
    grain.radius = r;
    world.addSwarm(grain);
    double lowest = 1.0;
    for (int step = 0; step < 5000; ++step) { // 10 s
        world.step(0.002);
        lowest = std::min(lowest, world.body(0).getPos().y);
    }
    EXPECT_GT(lowest, 0.05) << "caught in the air, never down at the nozzle";
    const dvec3 p = world.body(0).getPos(), q(world.swarm(0).position(0));
    EXPECT_NEAR(p.y, hover, 1e-3 * hover);
    EXPECT_LT(std::hypot(p.x, p.z), 1e-3) << "on the axis";
    EXPECT_LT(glm::length(world.body(0).getVel()), 1e-3) << "at rest";
    EXPECT_NEAR(q.y, hover, 1e-3 * hover) << "a swarm's grain alike";
    EXPECT_LT(std::hypot(q.x, q.z), 1e-3);
}
