// Every built-in scene's description says what `pba sim` measures on it; each test here runs the
// scene and holds it to its claim, with the same measurements `pba sim` prints (study::JetWatch
// for the blow dryer's figures).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "pba/blow_dryer.hpp"
#include "pba/scene/scene.hpp"
#include "pba/world.hpp"
#include "study/jet_watch.hpp"
#include "support/scene_claim.hpp"

using namespace pba;

namespace {

/// Runs `scene` for `duration` (its own without one) and returns what the jet watch saw.
study::JetWatch runWatched(Scene& scene, double duration = 0.0)
{
    World& world = scene.world;
    study::JetWatch jet(world);
    const auto steps = static_cast<long>(std::lround((duration > 0.0 ? duration : scene.duration) / scene.dt));
    {
        const study::JetWatch::Attachment attached = jet.attach(world); // as pba sim watches
        for (long n = 0; n < steps; ++n) {
            world.step(scene.dt);
            jet.record(world);
        }
    }
    return jet;
}

/// E(t) / E(0) of body i at every step of `duration` at `dt`.
std::vector<double> energyRatios(Scene scene, std::size_t i, double dt, double duration)
{
    World& world = scene.world;
    const double e0 = world.energy(i);
    std::vector<double> ratios;
    const auto steps = static_cast<long>(std::lround(duration / dt));
    for (long n = 0; n < steps; ++n) {
        world.step(dt);
        ratios.push_back(world.energy(i) / e0);
    }
    return ratios;
}

double mean(const std::vector<double>& x, std::size_t begin, std::size_t end)
{
    double sum = 0.0;
    for (std::size_t k = begin; k < end; ++k)
        sum += x[k];
    return sum / double(end - begin);
}

} // namespace

// "caught by the jet within a second and hovers in it for the rest of the minute, near 2.9 m";
// the bar: caught within 3 s, in the cone 70% of the minute, never in the hole for 1 s.
SCENE_CLAIM(SceneClaims, BlowDryerCatchesTheBallWithinASecondAndHoldsItAllMinute, "blow-dryer")
{
    Scene scene = loadScene("blow-dryer");
    ASSERT_DOUBLE_EQ(scene.duration, 60.0);
    const study::JetWatch jet = runWatched(scene);
    const study::BodyInJet ball = jet.bodies().at(0);
    ASSERT_TRUE(ball.caughtAt.has_value());
    EXPECT_LT(*ball.caughtAt, 1.0);
    EXPECT_GE(jet.fractionInCone(0), 0.95);
    EXPECT_GE(ball.longestStay, 59.0 - *ball.caughtAt); // caught for good: the rest of the minute
    EXPECT_NEAR(ball.meanHeightInCone, 2.9, 0.1);
    EXPECT_NEAR(scene.world.body(0).getPos().y, 2.9, 0.05); // hovering at the end
    EXPECT_LT(ball.longestInShaft, 1.0);
}

// A bare `pba` renders the first 10 s: from its catch on, the ball never leaves the cone.
SCENE_CLAIM(SceneClaims, BlowDryerHoversThroughTheDefaultVideo, "blow-dryer")
{
    Scene scene = loadScene("blow-dryer");
    World& world = scene.world;
    const study::JetWatch jet = runWatched(scene, 10.0);
    const auto ball = jet.bodies().at(0);
    ASSERT_TRUE(ball.caughtAt.has_value());
    EXPECT_NEAR(ball.longestStay, 10.0 - *ball.caughtAt, 2 * scene.dt);
    EXPECT_TRUE(insideBlowDryerCone(jet.field(), world.body(0).getPos()));
}

// "each hovers where the push balances its weight: the heavier, the lower (from 3.4 m for the
// 0.2 kg feather to 1.2 m for the 4 kg anvil) ... hold them in the jet all minute". The push on
// the axis is S (1 - h/H) (linear axial falloff), so the balance is h = H (1 - m g / S).
SCENE_CLAIM(SceneClaims, BlowDryerFlowHoldsEveryBallItCanLiftTheHeavierLower, "blow-dryer-flow")
{
    Scene scene = loadScene("blow-dryer-flow");
    const study::JetWatch jet = runWatched(scene);
    const auto balls = jet.bodies();
    ASSERT_EQ(balls.size(), 5u);
    const BlowDryerField& f = jet.field();
    for (std::size_t i = 0; i < balls.size(); ++i) {
        ASSERT_TRUE(balls[i].liftable) << balls[i].name;
        EXPECT_GE(jet.fractionInCone(i), 0.99) << balls[i].name; // the bar is a half
        EXPECT_LT(balls[i].longestInShaft, 1.0) << balls[i].name;
        const double balance = f.height * (1.0 - balls[i].mass * 9.81 / f.strength);
        EXPECT_NEAR(balls[i].meanHeightInCone, balance, 0.05) << balls[i].name;
        if (i > 0) {
            ASSERT_GT(balls[i].mass, balls[i - 1].mass);
            EXPECT_LT(balls[i].meanHeightInCone, balls[i - 1].meanHeightInCone) << balls[i].name;
        }
    }
    EXPECT_NEAR(balls.front().meanHeightInCone, 3.4, 0.05);
    EXPECT_NEAR(balls.back().meanHeightInCone, 1.2, 0.05);
}

// "rain into the cube room through the blow dryer's cone (over a third of them in it at once)
// and settle on the floor; those that fall into the hole are blown out of it within a tenth of
// a second" (the issue's bar: nothing lies in the hole for 1 s). Every particle is followed step
// by step; 20,000 of the scene's particles (each one's state depends on the seed and its index
// only) keep it short.
SCENE_CLAIM(SceneClaims, SwarmsSettleAndAreBlownOutOfTheHoleWithinATenthOfASecond, "blow-dryer-swarm", "fountain-1m")
{
    for (const char* name : {"blow-dryer-swarm", "fountain-1m"}) {
        Scene scene = loadScene(name);
        SwarmDesc desc = scene.world.swarm(0).desc();
        desc.count = 20000;
        scene.world.swarm(0) = Swarm(desc);
        const study::JetWatch jet = runWatched(scene);
        const auto& figures = jet.swarms().at(0);
        EXPECT_LT(figures.longestInShaft, 0.12) << name;
        EXPECT_GT(figures.peakInCone, desc.count / 3) << name;
        double height = 0.0;
        for (std::size_t i = 0; i < scene.world.swarm(0).size(); ++i)
            height += scene.world.swarm(0).position(i).y;
        EXPECT_LT(height / double(desc.count), 0.01) << name << ": settled on the floor";
    }
}

// "dt = 1/480 s (8 steps per 60 Hz frame)".
SCENE_CLAIM(SceneClaims, FountainStepsEightTimesA60HzFrame, "fountain-1m")
{
    const Scene scene = loadScene("fountain-1m");
    EXPECT_NEAR(scene.dt * 480.0, 1.0, 1e-12);
    EXPECT_EQ(scene.world.swarm(0).size(), 1000000u);
}

// "With the practical's reflect response, forward Euler gains height at every bounce while
// semi-implicit Euler keeps its bounce (its energy stays within 5% of the start)"; the issue
// asks it over 60 s at dt 0.01 and 0.05. Semi-implicit Euler's energy dips within each flight
// (by g^2 dt^2 / 2 a step, 12% of the drop's energy a second at dt 0.05) and the mirror gives it
// back, so "keeps" is measured on what does not oscillate: the energy averaged over the first
// and over the last ten seconds, and at the end.
SCENE_CLAIM(SceneClaims, IntegratorsShowThePracticalsLessonWithReflect, "integrators")
{
    const Scene scene = loadScene("integrators");
    EXPECT_EQ(scene.world.collisionResponse(), CollisionResponse::Reflect);
    const std::size_t forward = *scene.world.findBody("forward-euler");
    const std::size_t semi = *scene.world.findBody("semi-implicit-euler");
    for (const double dt : {0.01, 0.05}) {
        const std::vector<double> e = energyRatios(scene, semi, dt, 60.0);
        const std::size_t tenSeconds = static_cast<std::size_t>(std::lround(10.0 / dt));
        EXPECT_NEAR(mean(e, 0, tenSeconds), 1.0, 0.05) << "dt " << dt;
        EXPECT_NEAR(mean(e, e.size() - tenSeconds, e.size()), 1.0, 0.05) << "dt " << dt;
        EXPECT_NEAR(e.back(), 1.0, 0.05) << "dt " << dt;
        const std::vector<double> f = energyRatios(scene, forward, dt, scene.duration);
        EXPECT_GT(mean(f, f.size() - f.size() / 5, f.size()), 1.2) << "dt " << dt;
    }
}

// "without losing energy ... stays at its start to rounding".
SCENE_CLAIM(SceneClaims, BouncingCubeKeepsItsEnergyToRounding, "bouncing-cube")
{
    const Scene scene = loadScene("bouncing-cube");
    for (const double ratio : energyRatios(scene, 0, scene.dt, scene.duration))
        ASSERT_NEAR(ratio, 1.0, 1e-12);
}

// "Exact solution y(t) = 3 - cos(sqrt(10) t)": semi-implicit Euler at the scene's dt follows it
// to first order (its phase error grows as t dt omega^2 / 2: about 2% of the amplitude by 10 s).
SCENE_CLAIM(SceneClaims, SpringFollowsItsExactSolution, "spring")
{
    Scene scene = loadScene("spring");
    World& world = scene.world;
    double worst = 0.0;
    for (long n = 0; n < std::lround(scene.duration / scene.dt); ++n) {
        world.step(scene.dt);
        worst = std::max(worst, std::abs(world.body(0).getPos().y - (3.0 - std::cos(std::sqrt(10.0) * world.time()))));
    }
    EXPECT_LT(worst, 0.05);
}

// "every particle stays in the jet's cone for the whole run and none reaches the floor; ... holds
// the sheet's middle about half a metre above its corners, a dome between 2.4 and 2.9 m".
SCENE_CLAIM(SceneClaims, ClothInTheDryerBillowsAsADomeInTheCone, "cloth-in-the-dryer")
{
    Scene scene = loadScene("cloth-in-the-dryer");
    const study::JetWatch jet = runWatched(scene);
    const World& world = scene.world;
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        EXPECT_EQ(jet.fractionInCone(i), 1.0) << world.body(i).getName();
        EXPECT_EQ(jet.bodies().at(i).longestInShaft, 0.0) << world.body(i).getName();
        EXPECT_GT(world.body(i).getPos().y, 2.3) << world.body(i).getName();
        EXPECT_LT(world.body(i).getPos().y, 3.0) << world.body(i).getName();
    }
    const ClothLayout& sheet = scene.fabric.cloths.at(0);
    const double middle = world.body(sheet.at(4, 4)).getPos().y, corner = world.body(sheet.at(0, 0)).getPos().y;
    EXPECT_NEAR(middle - corner, 0.5, 0.15);
}

// "omega = sqrt(k/m) = 30 rad/s ... Exact solution y(t) = 3 - 0.1 cos(30 t)": velocity Verlet at a
// tenth of the scene's dt (omega dt = 0.03) follows it to second order; the stability limits it
// states are measured in tests/study/stability_test.cpp.
SCENE_CLAIM(SceneClaims, StiffSpringFollowsItsExactSolution, "stiff-spring")
{
    Scene scene = loadScene("stiff-spring");
    World& world = scene.world;
    world.body(0).setIntegrator(Integrator::VelocityVerlet);
    const double dt = scene.dt / 10.0;
    double worst = 0.0;
    for (long n = 0; n < std::lround(scene.duration / dt); ++n) {
        world.step(dt);
        worst = std::max(worst, std::abs(world.body(0).getPos().y - (3.0 - 0.1 * std::cos(30.0 * world.time()))));
    }
    // Verlet's phase error is t omega^3 dt^2 / 24 radians: 0.0056 by 5 s, 0.56 mm of a 0.1 m swing.
    EXPECT_LT(worst, 0.001);
    EXPECT_GT(worst, 1e-4);
}

// "at t = 2 v0 / (7 mu g) = 0.29 s; from then on it rolls at 5/7 v0 = 2.14 m/s".
SCENE_CLAIM(SceneClaims, RollingBallRollsFromTheClosedFormTime, "rolling")
{
    Scene scene = loadScene("rolling");
    World& world = scene.world;
    const auto& ball = static_cast<const RigidBody&>(world.body(0));
    const double r = 0.2, v0 = 3.0, tRoll = 2.0 * v0 / (7.0 * 0.3 * 9.81);
    EXPECT_NEAR(tRoll, 0.29, 0.005);
    double rolledAt = -1.0;
    for (long n = 0; n < std::lround(scene.duration / scene.dt); ++n) {
        world.step(scene.dt);
        const double slip = ball.getVel().x + ball.getAngularVelocity().z * r;
        if (rolledAt < 0.0 && std::abs(slip) < 1e-6)
            rolledAt = world.time();
    }
    EXPECT_NEAR(rolledAt, tRoll, 0.01 * tRoll);
    EXPECT_NEAR(ball.getVel().x, 5.0 / 7.0 * v0, 0.005);
    EXPECT_NEAR(5.0 / 7.0 * v0, 2.14, 0.005);
}

// "It turns over every 2.93 s, half the period T = 5.86 s that the complete elliptic integral of
// the first kind gives ... RK4 keeps its energy and |L| to 1e-9".
SCENE_CLAIM(SceneClaims, TennisRacketFlipsEveryHalfEllipticPeriod, "tennis-racket")
{
    Scene scene = loadScene("tennis-racket");
    World& world = scene.world;
    const auto& racket = static_cast<const RigidBody&>(world.body(0));
    const dmat3& inertia = racket.getInertiaBody();
    const double a = inertia[1][1], b = inertia[2][2], c = inertia[0][0]; // y < z < x
    const double e = racket.getRotationalKineticEnergy();
    const double l2 = glm::dot(racket.getAngularMomentum(), racket.getAngularMomentum());
    const double k2 = (c - b) * (l2 - 2.0 * e * a) / ((b - a) * (2.0 * e * c - l2));
    const double period = 4.0 * std::comp_ellint_1(std::sqrt(k2)) * std::sqrt(a * b * c / ((b - a) * (2.0 * e * c - l2)));
    EXPECT_NEAR(period, 5.86, 0.005);
    std::vector<double> flips;
    double previous = 1.0, worst = 0.0;
    for (long n = 0; n < std::lround(scene.duration / scene.dt); ++n) {
        world.step(scene.dt);
        const dvec3 w = glm::transpose(glm::mat3_cast(racket.getOrientation())) * racket.getAngularVelocity();
        if (w.z * previous < 0.0)
            flips.push_back(world.time());
        previous = w.z;
        worst = std::max({worst, std::abs(racket.getRotationalKineticEnergy() / e - 1.0),
                          std::abs(glm::dot(racket.getAngularMomentum(), racket.getAngularMomentum()) / l2 - 1.0)});
    }
    ASSERT_GE(flips.size(), 6u);
    for (std::size_t k = 1; k < flips.size(); ++k)
        EXPECT_NEAR(flips[k] - flips[k - 1], period / 2.0, 0.01 * period / 2.0);
    EXPECT_LT(worst, 1e-9);
}

// "holds them in the cone for the whole 20 s, the heavier the lower (on average 3.17, 2.85 and
// 2.00 m), and ... turns them: they tumble and spin".
SCENE_CLAIM(SceneClaims, BlowDryerBoxesHoverTumblingTheHeavierTheLower, "blow-dryer-boxes")
{
    Scene scene = loadScene("blow-dryer-boxes");
    World& world = scene.world;
    study::JetWatch jet(world);
    std::vector<double> spin(world.bodyCount(), 0.0);
    const long steps = std::lround(scene.duration / scene.dt);
    for (long n = 0; n < steps; ++n) {
        world.step(scene.dt);
        jet.record(world);
        for (std::size_t i = 0; i < world.bodyCount(); ++i)
            spin[i] += glm::length(static_cast<const RigidBody&>(world.body(i)).getAngularVelocity()) / double(steps);
    }
    const double heights[] = {3.17, 2.85, 2.00};
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        EXPECT_EQ(jet.fractionInCone(i), 1.0) << world.body(i).getName();
        EXPECT_NEAR(jet.bodies().at(i).meanHeightInCone, heights[i], 0.02) << world.body(i).getName();
        EXPECT_GT(spin[i], 0.1) << world.body(i).getName(); // rad/s on average: turning all the while
    }
}

// Every built-in scene has a claim test (SCENE_CLAIM: those above, the rope's and the cloth's in
// fabric_test.cpp, the rigid contact scenes' in contact_scene_claims_test.cpp), found by the
// scene's name: no list to keep by hand. Each registered claim names a built-in scene and a test
// this program has.
TEST(SceneClaims, EveryBuiltInSceneIsCovered)
{
    const auto& claims = test::sceneClaims();
    const std::vector<std::string> names = builtinSceneNames();
    ASSERT_FALSE(names.empty());
    for (const std::string& name : names)
        EXPECT_GT(claims.count(name), 0u) << "no SCENE_CLAIM test holds " << name << " to its description";
    std::set<std::string> tests;
    const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
    for (int s = 0; s < unit.total_test_suite_count(); ++s) {
        const ::testing::TestSuite& suite = *unit.GetTestSuite(s);
        for (int k = 0; k < suite.total_test_count(); ++k)
            tests.insert(std::string(suite.name()) + "." + suite.GetTestInfo(k)->name());
    }
    for (const auto& [scene, test] : claims) {
        EXPECT_NE(std::find(names.begin(), names.end(), scene), names.end()) << test << " claims " << scene
                                                                             << ", which is not a built-in scene";
        EXPECT_EQ(tests.count(test), 1u) << test << " is registered for " << scene << " but is not a test here";
    }
}
