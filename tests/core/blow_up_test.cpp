// Every blow-up is a BlowUpError naming the body, the step and the time: a rigid body whose spin
// overflows its orientation, one left with its centre inside the floor, and (BlowUpWatch) an
// energy that is not finite or that grows with no source to feed it. And what is not a blow-up
// is not called one: a source, a program's own force, a driven body, ordinary scenes.
#include "pba/blow_up_watch.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "pba/blow_dryer.hpp"
#include "pba/forces.hpp"
#include "pba/scene/scene.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

World roomWorld()
{
    World world;
    world.setRoom(Aabb{dvec3(-2.0, 0.0, -2.0), dvec3(2.0, 4.0, 2.0)});
    world.addForce(std::make_unique<Gravity>(dvec3(0.0, -9.81, 0.0)));
    return world;
}

/// What a run's blow-up was: the error, and for a NonFiniteStateError its quantity.
struct Caught {
    BlowUpError error;
    std::string quantity; ///< empty: not a NonFiniteStateError
};

/// Steps until the world or the watch throws; fails the test if neither does within `steps`.
Caught runUntilBlowUp(World& world, double dt, int steps, BlowUpWatch&& watch = {})
{
    for (int n = 0; n < steps; ++n) {
        try {
            world.step(dt);
            watch.check(world);
        } catch (const NonFiniteStateError& error) {
            return {error, error.quantity()};
        } catch (const BlowUpError& error) {
            return {error, ""};
        }
    }
    ADD_FAILURE() << "no blow-up in " << steps << " steps";
    return {BlowUpError("", 0, 0.0, ""), ""};
}

/// A particle on a spring anchored at the origin with rest length 0 (F = -k x) and no gravity,
/// released at rest 1 m out: its energy at the start is k / 2, all of it potential.
World oscillator(double stiffness, Integrator integrator)
{
    World world;
    Particle bob;
    bob.setName("bob");
    bob.setPos(dvec3(0.0, 1.0, 0.0));
    bob.setIntegrator(integrator);
    world.addParticle(bob);
    world.addForce(std::make_unique<Spring>(0, dvec3(0.0), stiffness, 0.0, 0.0));
    return world;
}

/// A program's own force: a steady push along x, with no answer to addsEnergy.
class Push final : public ForceBase<Push> {
public:
    std::string_view type() const override { return "push"; }
    dvec3 force(std::size_t, const Body&, const dvec3&, const dvec3&) const override { return dvec3(1.0, 0.0, 0.0); }
};

/// The README's first scene's jet: its axis pull flips direction across the axis, within a step
/// for a body that crosses it.
BlowDryerField firstScenesJet()
{
    return {.height = 3.5, .nozzleRadius = 0.2, .topRadius = 1.2, .strength = 30.0, .airSpeed = 15.0, .axisPull = 1.0};
}

} // namespace

// A body spinning so fast that its orientation's components overflow when squared normalises
// to (0, -0, 0, -0): that used to escape as std::invalid_argument from RigidBody::setOrientation
// ("an orientation must be a non-zero finite quaternion"); it is a state that is not finite.
TEST(RigidBlowUp, AnOrientationThatOverflowsIsANonFiniteStateNamingTheBody)
{
    World world;
    auto box = std::make_unique<RigidBody>(Shape::box(dvec3(0.3, 0.2, 0.1)), 500.0);
    box->setName("light");
    box->setAngularVelocity(dvec3(1e200, 3e199, -2e199));
    world.addBody(std::move(box));
    const auto [error, quantity] = runUntilBlowUp(world, 0.002, 10);
    EXPECT_EQ(quantity, "orientation") << error.what();
    EXPECT_EQ(error.body(), "light");
    EXPECT_EQ(error.step(), 1u);
    EXPECT_EQ(std::string(error.what()), "the orientation of body 'light' is not finite at step 1 (t = 0.002 s): try a "
                                         "smaller dt or another integrator");
    // Rolled back to the start: finite, with a unit orientation.
    const auto& b = static_cast<const RigidBody&>(world.body(0));
    EXPECT_EQ(b.getPos(), dvec3(0.0));
    EXPECT_NEAR(glm::length(b.getOrientation()), 1.0, 1e-12);
}

// Thrown into the floor or a wall at 1e50 m/s, a body used to end its step with its centre on
// the surface (its size lost to the rounding of a 1e47 m drift and its correction), a blow-up.
// The contact pipeline meets the surface at the time of arrival and takes the rest of the step
// from there: the body stops against it, whatever the integrator, and nothing blows up.
TEST(RigidBlowUp, ABallThrownAtTenToTheFiftyStopsAgainstTheSurfaceWithEveryIntegrator)
{
    for (const Integrator integrator : kRigidIntegrators) {
        World world;
        world.setRoom(Aabb{dvec3(0.0), dvec3(4.0)});
        auto ball = std::make_unique<RigidBody>(Shape::sphere(0.2), 1000.0);
        ball->setName("ball");
        ball->setPos(dvec3(0.3, 2.0, 2.0));
        ball->setVel(dvec3(-1e50, 0.0, 0.0));
        ball->setCor(0.0);
        ball->setIntegrator(integrator);
        world.addBody(std::move(ball));
        for (int k = 0; k < 10; ++k)
            world.step(0.001);
        EXPECT_NEAR(world.body(0).getPos().x, 0.2, 1e-9) << integratorName(integrator);
        EXPECT_NEAR(world.body(0).getVel().x, 0.0, 1e-9) << integratorName(integrator);
    }
    Scene scene = loadScene("rolling");
    scene.world.body(0).setVel(dvec3(0.0, -1e50, 0.0));
    for (int k = 0; k < 10; ++k)
        scene.world.step(scene.dt);
    EXPECT_NEAR(scene.world.body(0).getPos().y, 0.2, 1e-9);
}

// Forward Euler on x'' = -w^2 x multiplies the energy by exactly 1 + (w dt)^2 every step (the
// discrete oracle: |(1, -w dt; w dt, 1)|^2 on the scaled state). At w dt = 1 it doubles: the
// scale is the start's energy (at rest, no gravity), so the bound E0 + 100 E0 is first passed at
// step 7 (128 E0; step 6 has 64 E0).
TEST(BlowUpWatch, ForwardEulerOnASpringBlowsUpAtTheStepItsEnergyPassesTheBound)
{
    World world = oscillator(100.0, Integrator::ForwardEuler);
    BlowUpWatch watch(world);
    EXPECT_TRUE(watch.watchesGrowth());
    EXPECT_DOUBLE_EQ(watch.startEnergy(), 50.0);
    EXPECT_DOUBLE_EQ(watch.energyScale(), 50.0);
    EXPECT_DOUBLE_EQ(watch.energyBound(), 50.0 + BlowUpWatch::kEnergyGrowthLimit * 50.0);
    const BlowUpError error = runUntilBlowUp(world, 0.1, 20, std::move(watch)).error;
    EXPECT_EQ(error.step(), 7u);
    EXPECT_DOUBLE_EQ(error.time(), 0.7);
    EXPECT_EQ(error.body(), "bob");
    EXPECT_NE(std::string(error.what()).find("the energy of a system with no energy source rose from 50 J to 6400 J"),
              std::string::npos)
        << error.what();
    EXPECT_EQ(world.stepCount(), 7u); // the watch reads the state, it does not roll it back
}

// Semi-implicit Euler below its limit (w dt = 1 < 2) keeps a shadow energy: it never trips.
TEST(BlowUpWatch, AStableIntegratorNeverTripsIt)
{
    World world = oscillator(100.0, Integrator::SemiImplicitEuler);
    BlowUpWatch watch(world);
    for (int n = 0; n < 1000; ++n) {
        world.step(0.1);
        ASSERT_NO_THROW(watch.check(world)) << "step " << n;
    }
}

// The states stay finite while 1/2 m v^2 overflows: k = 1e300 at dt = 0.01 gives v = 1e298.
TEST(BlowUpWatch, AnEnergyThatIsNotFiniteIsANonFiniteStateNamingTheBody)
{
    World world = oscillator(1e300, Integrator::ForwardEuler);
    BlowUpWatch watch(world);
    world.step(0.01);
    ASSERT_TRUE(std::isfinite(world.body(0).getVel().y));
    try {
        watch.check(world);
        FAIL() << "an infinite energy passed";
    } catch (const NonFiniteStateError& error) {
        EXPECT_EQ(error.body(), "bob");
        EXPECT_EQ(error.quantity(), "energy");
        EXPECT_EQ(error.step(), 1u);
    }
}

// A source's work is its power summed by the trapezoid rule, exact for a steady push on a free
// particle under semi-implicit Euler (its speed, and so the push's power, rises by the same amount
// every step): the work is the kinetic energy gained, to rounding, and the energy rising ten
// thousand scales above its start is no blow-up.
TEST(BlowUpWatch, ASteadyPushsWorkIsTheEnergyItGives)
{
    World world;
    Particle puck;
    puck.setVel(dvec3(0.0, 1.0, 0.0)); // (a scale of 0.5 J: no gravity, no potential energy)
    world.addParticle(puck);
    world.addForce(std::make_unique<Push>());
    BlowUpWatch watch(world);
    EXPECT_TRUE(watch.hasSources());
    for (int n = 0; n < 1000; ++n) {
        world.step(0.1);
        ASSERT_NO_THROW(watch.check(world)) << "step " << n;
    }
    EXPECT_NEAR(watch.sourceWork(), 5000.0, 1e-9 * 5000.0);
    EXPECT_NEAR(world.totalEnergy() - watch.startEnergy(), watch.sourceWork(), 1e-9 * 5000.0);
}

// The work of a source whose force jumps within a step (the axis pull flips across the axis) and
// of a step split by a bounce (the exact response, restitution 1) is still exact: each stretch of
// a lone particle's flight is booked as its method took it. With no other force and bounces that
// keep the kinetic energy, the energy gained is that work, to rounding, under every method.
TEST(BlowUpWatch, ALoneParticlesSourceWorkIsExactUnderEveryMethod)
{
    for (const Integrator method : kAllIntegrators) {
        World world;
        world.setRoom({dvec3(-1.0, 0.0, -1.0), dvec3(1.0, 6.0, 1.0)});
        world.setCollisionResponse(CollisionResponse::Exact);
        world.addForce(std::make_unique<BlowDryer>(firstScenesJet()));
        Particle ball;
        ball.setPos(dvec3(-0.3, 0.5, 0.1));
        ball.setVel(dvec3(2.5, 0.0, -0.4));
        ball.setCor(1.0);
        ball.setIntegrator(method);
        world.addParticle(ball);
        BlowUpWatch watch(world);
        for (int n = 0; n < 2000; ++n) {
            world.step(0.01);
            ASSERT_NO_THROW(watch.check(world)) << integratorName(method) << " step " << n;
        }
        EXPECT_GT(world.bounceCount(0), 2u) << integratorName(method);
        EXPECT_GT(std::abs(watch.sourceWork()), 1.0) << integratorName(method); // (the drag slows it)
        EXPECT_NEAR(world.totalEnergy() - watch.startEnergy(), watch.sourceWork(), 1e-12 * std::abs(watch.sourceWork()))
            << integratorName(method);
    }
}

// The same for the members of a system of an explicit method, stepped as one: two balls joined by
// a spring of no stiffness (so that their energy is all kinetic) thrown across the jet's axis.
TEST(BlowUpWatch, ASystemsSourceWorkIsExactUnderEveryExplicitMethod)
{
    for (const Integrator method : kAllIntegrators) {
        World world;
        world.addForce(std::make_unique<BlowDryer>(firstScenesJet()));
        for (const double z : {0.1, -0.2}) {
            Particle ball;
            ball.setPos(dvec3(-0.3, 0.5, z));
            ball.setVel(dvec3(2.5, 0.0, -0.4));
            ball.setIntegrator(method);
            world.addParticle(ball);
        }
        world.addForce(std::make_unique<TwoBodySpring>(0, 1, 0.0, 0.3, 0.0));
        BlowUpWatch watch(world);
        for (int n = 0; n < 300; ++n) {
            world.step(0.01);
            ASSERT_NO_THROW(watch.check(world)) << integratorName(method) << " step " << n;
        }
        EXPECT_GT(std::abs(watch.sourceWork()), 1.0) << integratorName(method);
        EXPECT_NEAR(world.totalEnergy() - watch.startEnergy(), watch.sourceWork(), 1e-12 * std::abs(watch.sourceWork()))
            << integratorName(method);
    }
}

// A source that does no work hides no blow-up: with a blow dryer far from it, forward Euler on
// the spring trips at the same step as without one.
TEST(BlowUpWatch, ASourceThatDoesNoWorkHidesNoBlowUp)
{
    World dried = oscillator(100.0, Integrator::ForwardEuler);
    BlowDryerField far;
    far.nozzle = dvec3(100.0, 0.0, 0.0);
    dried.addForce(std::make_unique<BlowDryer>(far));
    BlowUpWatch watch(dried);
    EXPECT_TRUE(watch.hasSources());
    const BlowUpError error = runUntilBlowUp(dried, 0.1, 20, std::move(watch)).error;
    EXPECT_EQ(error.step(), 7u);
    EXPECT_EQ(error.body(), "bob");
    EXPECT_NE(error.reason().find("the energy rose from 50 J to 6400 J"), std::string::npos) << error.what();
    EXPECT_NE(error.reason().find("the 0 J of work its energy sources did"), std::string::npos) << error.what();
}

// A fixed body that the program moves drives the system with work no force accounts for: the
// growth rule is off.
TEST(BlowUpWatch, ADrivenBodyTurnsTheGrowthRuleOff)
{
    World driven = oscillator(100.0, Integrator::ForwardEuler);
    Particle anchor;
    anchor.setFixed(true);
    driven.addParticle(anchor);
    BlowUpWatch watch(driven);
    EXPECT_TRUE(watch.watchesGrowth());
    driven.body(1).setPos(dvec3(0.0, 0.1, 0.0)); // the program moves it
    for (int n = 0; n < 20; ++n) {
        driven.step(0.1);
        ASSERT_NO_THROW(watch.check(driven)) << "step " << n;
    }
}

// A world whose start energy is zero (a ball at rest on the floor, where its potential energy is
// zero) still has a scale: lifting it a metre. Resting there with every integrator trips nothing.
TEST(BlowUpWatch, AStartEnergyOfZeroStillHasAScale)
{
    for (const Integrator integrator : kAllIntegrators) {
        World world = roomWorld();
        Particle ball;
        ball.setIntegrator(integrator);
        ball.setCor(0.5);
        world.addParticle(ball);
        BlowUpWatch watch(world);
        EXPECT_EQ(watch.startEnergy(), 0.0);
        EXPECT_DOUBLE_EQ(watch.energyScale(), 9.81 * BlowUpWatch::kLiftHeight);
        for (int n = 0; n < 2000; ++n) {
            world.step(0.01);
            ASSERT_NO_THROW(watch.check(world)) << integratorName(integrator) << " step " << n;
        }
    }
}

// What the issue found exiting 0 inside the closed room: the rope with springs of stiffness
// 1e300 or dampers of 1e300, and the built-in rope at dt = 0.05 (energy x3440 by its end).
TEST(BlowUpWatch, RopesThatBlowUpInsideTheRoomAreCaught)
{
    const auto rope = [](double stiffness, double damping) {
        std::string json(builtinSceneText("rope"));
        const auto set = [&](const std::string& key, double value) {
            const std::size_t at = json.find("\"" + key + "\": ");
            const std::size_t end = json.find(',', at);
            json.replace(at, end - at, "\"" + key + "\": " + std::to_string(value));
        };
        if (stiffness > 0.0)
            set("stiffness", stiffness);
        if (damping > 0.0)
            set("damping", damping);
        return parseScene(json, "rope.json");
    };
    struct Case {
        Scene scene;
        double dt;
        int within;
    };
    std::vector<Case> cases;
    cases.push_back({rope(1e300, 0.0), 0.002, 5});
    cases.push_back({rope(0.0, 1e300), 0.002, 5});
    cases.push_back({loadScene("rope"), 0.05, 20});
    for (Case& c : cases) {
        BlowUpWatch watch(c.scene.world);
        const BlowUpError error = runUntilBlowUp(c.scene.world, c.dt, c.within, std::move(watch)).error;
        EXPECT_EQ(error.body().rfind("rope[", 0), 0u) << error.what();
        EXPECT_NE(error.reason().find("no energy source"), std::string::npos) << error.what();
    }
}

// The scenes, with a blow dryer or without, at their own dt with every integrator they can take
// (a rigid body does not take implicit-euler or xpbd), stay under the bound to their end, but for
// forward Euler on the stiff ones (the rope and the cloths, omega dt near 0.6, and the stiff
// spring, omega dt = 0.3, all grow by 1 + (omega dt)^2 a step: that is the blow-up the rule is for).
class OrdinaryScene : public testing::TestWithParam<const char*> {};

TEST_P(OrdinaryScene, AtItsOwnDtNeverTripsTheWatch)
{
    const std::string name = GetParam();
    const bool stiff = name == "rope" || name == "cloth" || name == "stiff-spring" || name == "cloth-in-the-dryer";
    for (const Integrator integrator : kEveryIntegrator) {
        if (integrator == Integrator::ForwardEuler && stiff)
            continue;
        Scene scene = loadScene(name);
        if (isSpringSystemMethod(integrator) && scene.world.hasRigidBodies())
            continue;
        for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
            if (!scene.world.body(i).isFixed())
                scene.world.body(i).setIntegrator(integrator);
        BlowUpWatch watch(scene.world);
        ASSERT_TRUE(watch.watchesGrowth());
        const auto steps = static_cast<int>(std::llround(scene.duration / scene.dt));
        for (int n = 0; n < steps; ++n) {
            scene.world.step(scene.dt);
            ASSERT_NO_THROW(watch.check(scene.world)) << integratorName(integrator) << ", step " << n;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(BlowUpWatch, OrdinaryScene,
                         testing::Values("bouncing-cube", "integrators", "spring", "stiff-spring", "rope", "cloth",
                                         "dice", "rolling", "tennis-racket", "blow-dryer", "blow-dryer-flow",
                                         "balls-in-the-dryer", "cloth-in-the-dryer", "blow-dryer-boxes", "ping-pong"),
                         [](const testing::TestParamInfo<const char*>& each) {
                             std::string name = each.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });
