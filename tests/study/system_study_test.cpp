// A rope or a cloth has no exact solution: the study follows the whole system (its total energy
// and centre of mass) against a fine-dt run of the same method, never one particle.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <set>

#include "study/findings.hpp"
#include "study/plots.hpp"
#include "study/study.hpp"
#include "compare_run.hpp"
#include "support/run_command.hpp"

using namespace pba;
using namespace pba::test;

namespace {

/// The rope for 1.2 s: it swings down and first strikes the floor at about 0.86 s.
const study::StudyResult& ropeStudy(study::StudyConfig& config)
{
    config.scene = loadScene("rope");
    config.integrators = {Integrator::ForwardEuler, Integrator::SemiImplicitEuler, Integrator::RK4};
    config.collisions = {CollisionResponse::Exact, CollisionResponse::Reflect};
    config.dts = {0.001, 0.002};
    config.duration = 1.2;
    config.jobs = 2;
    static const study::StudyResult result = study::runStudy(config);
    return result;
}

} // namespace

TEST(SystemStudy, ARopeIsFollowedAsAWholeAgainstAQuarterDtReference)
{
    study::StudyConfig config;
    const auto& result = ropeStudy(config);
    EXPECT_TRUE(result.followsSystem);
    EXPECT_DOUBLE_EQ(result.referenceDt, 0.00025);
    const auto* row = study::findRun(result, Integrator::SemiImplicitEuler, CollisionResponse::Reflect, 0.002);
    ASSERT_NE(row, nullptr);
    EXPECT_EQ(row->particle, study::kSystemRow);

    // The system row's energy is the world's total: the same run stepped here, totalEnergy() at
    // its end over at its start.
    World world = config.scene.world;
    world.setCollisionResponse(CollisionResponse::Reflect);
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (!world.body(i).isFixed())
            world.body(i).setIntegrator(Integrator::SemiImplicitEuler);
    const double e0 = world.totalEnergy();
    for (int n = 0; n < 600; ++n)
        world.step(0.002);
    EXPECT_NEAR(row->energyRatioEnd, world.totalEnergy() / e0, 1e-9);
    EXPECT_LT(row->energyRatioEnd, 1.0); // damping, drag and a bounce take energy out
    EXPECT_GT(row->bounces, 0u);
    EXPECT_NEAR(row->firstImpactAt, 0.86, 0.05);
}

// Before the first impact the motion is smooth, so the centre of mass's distance from the
// reference falls with dt at the method's order: halving dt halves it for semi-implicit Euler
// (order 1) and divides it by about 16 for RK4 (order 4). The reference's own error (at a quarter
// of dt) changes the ratio by a factor (1 - 4^-p) / (1 - 2^-p): log2 of it is 0.1 for RK4.
TEST(SystemStudy, TheCentreOfMassErrorBeforeTheFirstImpactFallsAtTheMethodsOrder)
{
    study::StudyConfig config;
    const auto& result = ropeStudy(config);
    for (auto [integrator, order] : {std::pair{Integrator::SemiImplicitEuler, 1}, std::pair{Integrator::RK4, 4}}) {
        const auto* coarse = study::findRun(result, integrator, CollisionResponse::Reflect, 0.002);
        const auto* fine = study::findRun(result, integrator, CollisionResponse::Reflect, 0.001);
        ASSERT_TRUE(coarse && fine);
        const double measured = std::log2(coarse->errorBeforeImpact / fine->errorBeforeImpact);
        EXPECT_NEAR(measured, order, 0.5) << integratorName(integrator);
        EXPECT_GE(coarse->maxPositionError, coarse->errorBeforeImpact);
    }
}

// Every particle of a rope is coupled, so `exact` acts as `reflect`: the same runs, shown once
// and said why.
TEST(SystemStudy, ExactIsShownAsReflectWithTheReasonWhenEveryParticleIsCoupled)
{
    study::StudyConfig config;
    const auto& result = ropeStudy(config);
    EXPECT_TRUE(result.exactActsAsReflect);
    for (double dt : config.dts) {
        const auto* e = study::findRun(result, Integrator::SemiImplicitEuler, CollisionResponse::Exact, dt);
        const auto* r = study::findRun(result, Integrator::SemiImplicitEuler, CollisionResponse::Reflect, dt);
        EXPECT_EQ(e->energyRatioEnd, r->energyRatioEnd);
        EXPECT_EQ(e->maxPositionError, r->maxPositionError);
    }
    EXPECT_EQ(study::distinctResponses(config, result), std::vector<CollisionResponse>{CollisionResponse::Reflect});
    const std::string text = study::findings(config, result);
    EXPECT_NE(text.find("**`exact` is `reflect` here.**"), std::string::npos) << text;
}

// A linear axis with one method at 70 times the start flattens the others into one line: the
// energy plot turns logarithmic, and each method keeps its own dashes and point type.
TEST(SystemStudy, TheEnergyPlotIsLogarithmicOverDecadesAndEveryLineHasItsOwnDashes)
{
    study::StudyConfig config;
    const auto& result = ropeStudy(config);
    const std::string script = study::plotScript(freshDir("system_plots"), config, result);
    const std::size_t begin = script.find("set output 'energy.png'");
    ASSERT_NE(begin, std::string::npos);
    const std::string energy = script.substr(begin, script.find("set output", begin + 1) - begin);
    EXPECT_NE(energy.find("set logscale y"), std::string::npos) << energy;
    EXPECT_NE(energy.find("total energy"), std::string::npos) << energy;
    std::set<std::string> dashes;
    const std::regex style(R"(with linespoints lw 2 dt (\S+) pt (\d+))");
    for (auto it = std::sregex_iterator(energy.begin(), energy.end(), style); it != std::sregex_iterator(); ++it)
        dashes.insert((*it)[1].str() + " " + (*it)[2].str());
    EXPECT_EQ(dashes.size(), config.integrators.size()) << energy;
    EXPECT_NE(script.find("height of the centre of mass"), std::string::npos);
}

TEST(PbaCompare, ARopeReportSaysWhatItMeasuresAndShowsNoNanNorInfinity)
{
    const auto dir = freshDir("compare_rope");
    const CompareRun run =
        runCompare("rope --duration 1.2 --dt 0.001,0.002 --integrators forward-euler,semi-implicit-euler", dir);
    ASSERT_TRUE(run.ok()) << run.result.err;
    const std::string& report = run.report;
    EXPECT_FALSE(std::regex_search(report, std::regex(R"(\bnan\b|\binf\b)", std::regex::icase))) << report;
    EXPECT_EQ(report.find("compared with its exact solution"), std::string::npos) << report;
    EXPECT_NE(report.find("the reference is a run of the same method and response at dt = 0.00025 s"), std::string::npos)
        << report;
    EXPECT_NE(report.find("## Total energy (every body) at the end over at the start, `reflect` response (and "
                          "`exact`, the same runs here)"),
              std::string::npos)
        << report;
    EXPECT_EQ(report.find("`exact` response\n"), std::string::npos) << report; // no table of its own
    EXPECT_NE(report.find("## Centre of mass"), std::string::npos) << report;
    EXPECT_NE(report.find("blew up at t = "), std::string::npos) << report;
    EXPECT_EQ(report.find("rope[1]"), std::string::npos) << report;
}

// The report says the impacts make the whole run's error only where they do: on the rope over
// 3 s, at the smallest dt, it is over ten times the error before the first impact; on the cloth
// over 1.2 s (two rows touch the wall lightly) it is not, and the report gives the range alone.
TEST(PbaCompare, TheImpactsAreBlamedForTheWholeRunsErrorOnlyWhereTheyMakeIt)
{
    const auto dir = freshDir("compare_impacts");
    const std::string sentence = "At the smallest dt that is over ten times the distance before the impact";
    const std::string common = " --dt 0.001,0.002 --integrators semi-implicit-euler --collisions reflect";
    const CompareRun rope = runCompare("rope --duration 3" + common, dir / "rope");
    ASSERT_TRUE(rope.ok()) << rope.result.err;
    const std::string& ropeReport = rope.report;
    EXPECT_NE(ropeReport.find(sentence), std::string::npos) << ropeReport;
    const CompareRun cloth = runCompare("cloth --duration 1.2" + common, dir / "cloth");
    ASSERT_TRUE(cloth.ok()) << cloth.result.err;
    const std::string& clothReport = cloth.report;
    EXPECT_NE(clothReport.find("Over the whole run"), std::string::npos) << clothReport;
    EXPECT_EQ(clothReport.find(sentence), std::string::npos) << clothReport;
}
