// The rotation study against the exact period of the tennis racket's flips, and each method's
// character on a free tumbling body: RK4 converges to the elliptic integral's period, the
// implicit gyroscopic step stays bounded where the explicit Eulers gain energy.
#include <gtest/gtest.h>

#include <cmath>

#include "study/rotation_study.hpp"

using namespace pba;

namespace {

const study::RotationRun& runOf(const study::RotationResult& result, Integrator integrator, double dt)
{
    for (const auto& r : result.runs)
        if (r.integrator == integrator && r.dt == dt)
            return r;
    throw std::runtime_error("no such run");
}

/// The tennis racket spun at `spin` (world frame), studied with RK4 at dt 0.001.
study::RotationConfig racketSpunAt(const dvec3& spin)
{
    study::RotationConfig config;
    config.scene = loadScene("tennis-racket");
    static_cast<RigidBody&>(config.scene.world.body(0)).setAngularVelocity(spin);
    config.integrators = {Integrator::RK4};
    config.dts = {0.001};
    return config;
}

} // namespace

TEST(RotationStudy, TennisRacketFlipsAtTheEllipticPeriodAndEachMethodShowsItsCharacter)
{
    study::RotationConfig config;
    config.scene = loadScene("tennis-racket");
    config.dts = {0.001, 0.05};
    config.duration = 20.0;
    const study::RotationResult result = study::runRotationStudy(config);
    EXPECT_EQ(result.body, "racket");
    EXPECT_EQ(result.intermediateAxis, 2);
    EXPECT_NEAR(result.exactPeriod, 5.86, 0.005);
    ASSERT_EQ(result.runs.size(), kRigidIntegrators.size() * 2);
    // At a small dt RK4's flips keep the exact period (the bar is 1%), and it keeps
    // energy and |L|.
    const auto& rk4 = runOf(result, Integrator::RK4, 0.001);
    EXPECT_GE(rk4.flips, 6u);
    EXPECT_NEAR(rk4.flipPeriod, result.exactPeriod, 1e-6 * result.exactPeriod);
    EXPECT_LT(rk4.maxEnergyDrift, 1e-9);
    EXPECT_LT(rk4.maxMomentumDrift, 1e-12);
    // At dt = 0.05 forward Euler's energy grows (here it almost quadruples), the implicit
    // gyroscopic step's only falls, and its flips keep the period within 1%.
    const auto& euler = runOf(result, Integrator::ForwardEuler, 0.05);
    const auto& implicit = runOf(result, Integrator::ImplicitGyroscopic, 0.05);
    EXPECT_GT(euler.energyRatioEnd, 3.0);
    EXPECT_LT(implicit.energyRatioEnd, 1.0);
    EXPECT_LT(implicit.maxEnergyDrift, 1.0);
    EXPECT_NEAR(implicit.flipPeriod, result.exactPeriod, 0.01 * result.exactPeriod);
}

TEST(RotationStudy, ASymmetricBodyHasNoFlipPeriod)
{
    RigidBody cylinder(Shape::cylinder(0.2, 0.5), 500.0);
    cylinder.setAngularVelocity(dvec3(0.1, 5.0, 0.0));
    EXPECT_TRUE(std::isnan(study::torqueFreeFlipPeriod(cylinder)));
    RigidBody box(Shape::box(dvec3(0.1, 0.6, 0.3)), 500.0);
    box.setAngularVelocity(dvec3(0.0, 0.0, 6.0)); // exactly about the intermediate axis: no flip
    EXPECT_TRUE(std::isnan(study::torqueFreeFlipPeriod(box)));
}

// The other side of the separatrix (L^2 > 2 E I2, a nudge towards the largest axis): the same
// period with the smallest and largest moments swapped, as the RK4 run measures it.
TEST(RotationStudy, FlipPeriodHoldsOnBothSidesOfTheSeparatrix)
{
    // Nudged towards x, the largest moment.
    const study::RotationResult result = study::runRotationStudy(racketSpunAt(dvec3(0.05, 0.0, 6.0)));
    ASSERT_FALSE(std::isnan(result.exactPeriod));
    EXPECT_NEAR(result.runs.at(0).flipPeriod, result.exactPeriod, 1e-5 * result.exactPeriod);
}

// Spun about its largest axis and nudged, a box wobbles: its intermediate spin changes sign with
// the polhode's period, but it never flips, and the study does not say it does.
TEST(RotationStudy, ABoxSpunNearItsLargestAxisWobblesAndDoesNotFlip)
{
    study::RotationConfig config = racketSpunAt(dvec3(6.0, 0.0, 0.3)); // about x, the largest moment
    config.duration = 4.0;
    const study::RotationResult result = study::runRotationStudy(config);
    EXPECT_FALSE(result.flips);
    ASSERT_FALSE(std::isnan(result.exactPeriod));
    EXPECT_NEAR(result.runs.at(0).flipPeriod, result.exactPeriod, 1e-4 * result.exactPeriod);
    config = racketSpunAt(dvec3(0.05, 0.0, 6.0)); // the racket's own: about the intermediate axis
    config.duration = 4.0;
    EXPECT_TRUE(study::runRotationStudy(config).flips);
}

// The methods studied move the rigid bodies only: the hanging crate's rope keeps its implicit
// Euler (stiff and damped for it, it blew up within steps under every explicit method, and every
// run of the study with it).
TEST(RotationStudy, RopesKeepTheirOwnIntegrator)
{
    study::RotationConfig config;
    config.scene = loadScene("hanging-crate");
    config.dts = {0.002};
    config.duration = 0.5;
    const study::RotationResult result = study::runRotationStudy(config);
    EXPECT_EQ(result.body, "crate");
    ASSERT_EQ(result.runs.size(), kRigidIntegrators.size());
    for (const study::RotationRun& run : result.runs) {
        EXPECT_TRUE(std::isnan(run.blewUpAt)) << integratorName(run.integrator) << " blew up at " << run.blewUpAt;
        EXPECT_EQ(run.steps, 250u) << integratorName(run.integrator);
    }
}
