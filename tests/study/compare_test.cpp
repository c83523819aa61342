// The integrator study's numbers against oracles, and `pba compare`'s files.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include <stb_image.h>

#include "render/palette.hpp"
#include "study/findings.hpp"
#include "study/plots.hpp"
#include "study/exact_solution.hpp"
#include "study/study.hpp"
#include "compare_run.hpp"
#include "support/run_command.hpp"

using namespace pba;
using namespace pba::test;

namespace {

/// The default study on the integrators scene, shortened to 6 s (four bounces) to stay fast.
const study::StudyResult& defaultStudy()
{
    static const study::StudyResult result = [] {
        study::StudyConfig config;
        config.scene = loadScene("integrators");
        config.duration = 6.0;
        config.jobs = 2;
        return study::runStudy(config);
    }();
    return result;
}

std::vector<const study::ParticleResult*> select(Integrator integrator, CollisionResponse collision)
{
    std::vector<const study::ParticleResult*> rows;
    for (const auto& r : defaultStudy().runs)
        if (r.integrator == integrator && r.collision == collision && r.particle == "forward-euler")
            rows.push_back(&r);
    return rows; // in increasing dt
}

/// A short study of `scene` over the given dt.
study::StudyResult shortStudy(study::StudyConfig& config, const std::string& scene, std::vector<double> dts,
                              double duration)
{
    config.scene = loadScene(scene);
    config.dts = std::move(dts);
    config.duration = duration;
    config.jobs = 2;
    return study::runStudy(config);
}

/// What a report must never say, whatever the dt: a number that is not one, a range or a
/// comparison of one value with itself, a heading with nothing under it.
void expectEverySentenceMeaningful(const std::string& text)
{
    EXPECT_EQ(std::regex_search(text, std::regex("nan", std::regex::icase)), false) << text;
    EXPECT_FALSE(std::regex_search(text, std::regex(R"(from ([0-9.e-]*[0-9]) to \1(?![0-9]|\.[0-9]))"))) << text;
    EXPECT_FALSE(std::regex_search(text, std::regex(R"(at dt = ([0-9.e-]*[0-9])(?![0-9]|\.[0-9])(?:(?!\. )[^\n])*at dt = \1(?![0-9]|\.[0-9]))"))) << text;
    std::size_t start = 0;
    while (start < text.size()) {
        const std::size_t end = std::min(text.find("\n\n", start), text.size());
        const std::string paragraph = text.substr(start, end - start);
        EXPECT_FALSE(std::regex_match(paragraph, std::regex(R"(\s*\*\*[^*]*\*\*\s*)"))) << "empty paragraph in\n" << text;
        start = end + 2;
    }
}

} // namespace

TEST(IntegratorStudy, ForwardEulerGainsMoreEnergyTheLargerDtInEveryResponse)
{
    for (CollisionResponse collision : kAllCollisionResponses) {
        const auto rows = select(Integrator::ForwardEuler, collision);
        ASSERT_EQ(rows.size(), 8u);
        for (std::size_t i = 0; i < rows.size(); ++i) {
            EXPECT_GT(rows[i]->energyRatioEnd, 1.0) << collisionResponseName(collision) << " dt " << rows[i]->dt;
            if (i > 0) {
                EXPECT_GT(rows[i]->energyRatioEnd, rows[i - 1]->energyRatioEnd) << collisionResponseName(collision);
            }
        }
    }
}

TEST(IntegratorStudy, SemiImplicitEulerKeepsItsEnergyWithReflect)
{
    for (const auto* r : select(Integrator::SemiImplicitEuler, CollisionResponse::Reflect))
        if (r->dt <= 0.05) {
            EXPECT_NEAR(r->meanEnergyRatio, 1.0, 0.05) << "dt " << r->dt;
        }
}

TEST(IntegratorStudy, VerletAndRK4ReproduceTheBouncePeriodAndApexWithExactImpacts)
{
    for (Integrator integrator : {Integrator::VelocityVerlet, Integrator::RK4}) {
        for (const auto* r : select(integrator, CollisionResponse::Exact)) {
            EXPECT_GE(r->bounces, 4u);
            EXPECT_NEAR(r->periodError, 0.0, 1e-9) << integratorName(integrator) << " dt " << r->dt;
            EXPECT_NEAR(r->apexRatioLast, 1.0, 1e-9) << integratorName(integrator) << " dt " << r->dt;
            EXPECT_LT(r->maxPositionError, 1e-9) << integratorName(integrator) << " dt " << r->dt;
            EXPECT_NEAR(r->energyRatioEnd, 1.0, 1e-9);
        }
    }
}

TEST(IntegratorStudy, MeasuredOrdersAreWithinAThirdOfTheTheory)
{
    ASSERT_EQ(defaultStudy().orders.size(), 4u);
    for (const auto& o : defaultStudy().orders)
        EXPECT_NEAR(o.measured, o.expected, 0.3) << integratorName(o.integrator);
}

// The plots follow each run's first moving particle (findRun's), so only its series is kept: a
// series for every particle of every run took 1.9 GB for a 40 x 40 cloth over 1 s.
TEST(IntegratorStudy, KeepsTheSeriesOfEachRunsFirstMovingParticleOnly)
{
    std::size_t followed = 0, others = 0;
    for (const auto& r : defaultStudy().runs) {
        const bool first = study::findRun(defaultStudy(), r.integrator, r.collision, r.dt) == &r;
        if (first) {
            ++followed;
            EXPECT_GT(r.series.t.size(), 1u) << r.particle;
            EXPECT_EQ(r.series.y.size(), r.series.t.size()) << r.particle;
        } else {
            ++others;
            EXPECT_TRUE(r.series.t.empty() && r.series.y.empty() && r.series.energyRatio.empty()) << r.particle;
        }
    }
    EXPECT_EQ(followed, 4u * 3u * 8u);
    EXPECT_EQ(others, followed); // the scene's second moving particle
}

TEST(PbaCompare, WritesEveryRowAndPlotsAndIsTheSameWhateverTheJobs)
{
    const auto dir = freshDir("compare");
    const std::string common = "compare --duration 3 --dt 0.001,0.01,0.05 ";
    const CommandResult one = runPba(common + "--jobs 1 --out " + (dir / "one").string());
    ASSERT_EQ(one.exitCode, 0) << one.err;
    const CommandResult two = runPba(common + "--jobs 2 --out " + (dir / "two").string());
    ASSERT_EQ(two.exitCode, 0) << two.err;
    for (const char* file : {"results.csv", "orders.csv", "report.md"})
        EXPECT_EQ(readFile(dir / "one" / file), readFile(dir / "two" / file)) << file;

    // One row per integrator, collision response, dt and moving particle.
    std::istringstream csv(readFile(dir / "one/results.csv"));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line.rfind("integrator,collision,dt,particle,", 0), 0u);
    std::set<std::string> keys;
    while (std::getline(csv, line)) {
        std::vector<std::string> cells;
        std::stringstream fields(line);
        for (std::string cell; std::getline(fields, cell, ',');)
            cells.push_back(cell);
        ASSERT_EQ(cells.size(), 13u) << line;
        for (std::size_t i = 4; i < cells.size(); ++i)
            EXPECT_NO_THROW((void)std::stod(cells[i])) << line;
        keys.insert(cells[0] + cells[1] + cells[2] + cells[3]);
    }
    EXPECT_EQ(keys.size(), 4u * 3u * 3u * 2u);

    for (const char* plot : {"height.png", "energy.png", "convergence.png"}) {
        int w = 0, h = 0, n = 0;
        unsigned char* data = stbi_load((dir / "one" / plot).c_str(), &w, &h, &n, 3);
        ASSERT_NE(data, nullptr) << plot;
        std::set<int> colours;
        for (int i = 0; i < w * h; i += 7)
            colours.insert(data[3 * i] << 16 | data[3 * i + 1] << 8 | data[3 * i + 2]);
        stbi_image_free(data);
        EXPECT_GT(colours.size(), 8u) << plot << " is blank";
    }
    const std::string report = readFile(dir / "one/report.md");
    EXPECT_NE(report.find("## Findings"), std::string::npos);
    EXPECT_NE(report.find("![height](height.png)"), std::string::npos);
    EXPECT_NE(one.out.find("order of accuracy"), std::string::npos);
}

// The progress bar showed "0.0 s left" while no run had finished (the estimate divided by a
// fraction of 0): before the first it says it is estimating. Each run here takes seconds.
TEST(PbaCompare, TheProgressBarEstimatesNothingBeforeARunHasFinished)
{
    const auto dir = freshDir("compare_progress");
    RunOptions options;
    options.stderrOnTerminal = true;
    options.stopAfterMs = 2500; // the bar appears after a second; the first run ends after several
    options.stopSignal = SIGINT;
    const CommandResult r = runPbaArgv({"compare", "--dt", "1e-6", "--out", (dir / "study").string()}, options);
    EXPECT_EQ(r.exitCode, 128 + SIGINT) << r.err;
    EXPECT_TRUE(std::regex_search(r.err, std::regex(R"(0/16  \d+\.\d s elapsed, estimating the time left)"))) << r.err;
    EXPECT_EQ(r.err.find(" s left"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "study" / "report.md"));
}

TEST(PbaCompare, OneDtReportReadsTrueAndTheSpringHasOneTable)
{
    const auto dir = freshDir("compare_short");
    const CommandResult one = runPba("compare --duration 2 --dt 0.3 --out " + (dir / "one").string());
    ASSERT_EQ(one.exitCode, 0) << one.err;
    const std::string report = readFile(dir / "one/report.md");
    expectEverySentenceMeaningful(report);
    EXPECT_NE(report.find("dt = 0.3 s."), std::string::npos) << report;
    EXPECT_NE(report.find("| not measured |"), std::string::npos) << report;
    EXPECT_EQ(one.out.find("nan"), std::string::npos) << one.out;

    const CommandResult spring = runPba("compare spring --duration 2 --dt 0.01,0.02 --out " + (dir / "spring").string());
    ASSERT_EQ(spring.exitCode, 0) << spring.err;
    const std::string springReport = readFile(dir / "spring/report.md");
    std::size_t tables = 0;
    for (std::size_t at = springReport.find("## Energy at the end"); at != std::string::npos;
         at = springReport.find("## Energy at the end", at + 1))
        ++tables;
    EXPECT_EQ(tables, 1u) << springReport;
    EXPECT_NE(springReport.find("nothing collides"), std::string::npos) << springReport;
}

TEST(PbaCompare, BadOptionsAreBadInput)
{
    EXPECT_EQ(runPba("compare --integrators leapfrog --out /tmp/x").exitCode, 2);
    EXPECT_EQ(runPba("compare --collisions bounce --out /tmp/x").exitCode, 2);
    EXPECT_EQ(runPba("compare --dt 0.01,-1 --out /tmp/x").exitCode, 2);
    // A rigid scene's study takes the rigid bodies' methods: a springs' method is refused up
    // front, naming the flag, and nothing is written.
    const auto dir = freshDir("compare-rigid-method");
    const CommandResult rigid = runPba("compare dice --integrators rk4,implicit-euler --out " + (dir / "study").string());
    EXPECT_EQ(rigid.exitCode, 2) << rigid.err;
    EXPECT_EQ(rigid.err.rfind("pba: error: --integrators: builtin:dice is a scene with rigid bodies", 0), 0u) << rigid.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "study"));
}

TEST(IntegratorFindings, OneDtGivesNoRangeNoComparisonAndNoOrder)
{
    study::StudyConfig config;
    const auto result = shortStudy(config, "integrators", {0.3}, 3.0);
    const std::string text = study::findings(config, result);
    expectEverySentenceMeaningful(text);
    EXPECT_NE(text.find("at dt = 0.3"), std::string::npos) << text;
    // An order needs two dt in the asymptotic range, and the report says so instead of a number.
    EXPECT_NE(text.find("are not measured"), std::string::npos) << text;
    EXPECT_NE(text.find("none of the dt given is"), std::string::npos) << text;
    EXPECT_EQ(text.find("Each halving"), std::string::npos) << text;
    for (const auto& o : result.orders)
        EXPECT_EQ(study::orderText(o), "not measured");
    EXPECT_EQ(study::describeDts(config.dts), "dt = 0.3 s");
}

TEST(IntegratorFindings, TwoDtWithOneInTheAsymptoticRangeSayWhyThereIsNoOrder)
{
    study::StudyConfig config;
    const auto result = shortStudy(config, "integrators", {0.01, 0.05}, 3.0);
    const std::string text = study::findings(config, result);
    expectEverySentenceMeaningful(text);
    EXPECT_NE(text.find("at dt = 0.01 and"), std::string::npos) << text;
    EXPECT_NE(text.find("only 0.01 is"), std::string::npos) << text;
    EXPECT_EQ(text.find("Each halving"), std::string::npos) << text;
    EXPECT_EQ(study::describeDts(config.dts), "dt = 0.01 and 0.05 s");
}

TEST(IntegratorFindings, TwoDtInTheAsymptoticRangeGiveAnOrder)
{
    study::StudyConfig config;
    const auto result = shortStudy(config, "integrators", {0.005, 0.01}, 3.0);
    const std::string text = study::findings(config, result);
    expectEverySentenceMeaningful(text);
    for (const auto& o : result.orders) {
        EXPECT_EQ(o.fitted.size(), 2u);
        EXPECT_NEAR(o.measured, o.expected, 0.3) << integratorName(o.integrator);
    }
    EXPECT_NE(text.find("Each halving"), std::string::npos) << text;
}

TEST(IntegratorFindings, EightDtStateEveryFinding)
{
    study::StudyConfig config;
    config.scene = loadScene("integrators");
    const std::string text = study::findings(config, defaultStudy());
    expectEverySentenceMeaningful(text);
    for (const char* finding : {"**Forward Euler gains energy.**", "collision response decides the verdict",
                                "with exact impacts is exact", "gain energy with `reflect`", "Each halving"})
        EXPECT_NE(text.find(finding), std::string::npos) << finding << " missing from\n" << text;
    EXPECT_NE(text.find("over every dt from 0.0005 to 0.1"), std::string::npos) << text;
    EXPECT_EQ(study::describeDts(config.dts), "dt from 0.0005 to 0.1 s (8 values)");
}

TEST(IntegratorFindings, ReflectGainOfVerletAndRK4IsTheMirrorsAndExplained)
{
    // With `reflect`, a step ending a depth d below the floor is mirrored to d above it with the
    // end-of-step speed: the apex rises by 2 d, d in [0, |v| dt). Verlet and RK4 are exact in
    // flight, so each bounce's relative gain lies in (0, 2 |v| dt / h], |v| the largest impact
    // speed, sqrt(2 g h E(end)/E(0)).
    const double h = 2.0, g = 9.81;
    for (Integrator integrator : {Integrator::VelocityVerlet, Integrator::RK4})
        for (const auto* r : select(integrator, CollisionResponse::Reflect)) {
            ASSERT_GT(r->bounces, 0u);
            EXPECT_GT(r->energyRatioEnd, 1.0) << "dt " << r->dt;
            const double perBounce = std::pow(r->energyRatioEnd, 1.0 / double(r->bounces)) - 1.0;
            EXPECT_LE(perBounce, 2.0 * std::sqrt(2.0 * g * h * r->energyRatioEnd) * r->dt / h) << "dt " << r->dt;
        }
    study::StudyConfig config;
    config.scene = loadScene("integrators");
    const std::string text = study::findings(config, defaultStudy());
    EXPECT_NE(text.find("**velocity-verlet and rk4 gain energy with `reflect`.**"), std::string::npos) << text;
    EXPECT_NE(text.find("the time it spent below the surface is not given back"), std::string::npos) << text;
    const auto* atTypical = study::findRun(defaultStudy(), Integrator::VelocityVerlet, CollisionResponse::Reflect, 0.01);
    ASSERT_NE(atTypical, nullptr);
    char measured[64];
    std::snprintf(measured, sizeof measured, "%.4f times the start at dt = 0.01", atTypical->energyRatioEnd);
    EXPECT_NE(text.find(measured), std::string::npos) << measured << " missing from\n" << text;

    // No gain, no sentence: without `reflect` the paragraph is not there.
    study::StudyConfig exactOnly;
    exactOnly.collisions = {CollisionResponse::Exact};
    const auto result = shortStudy(exactOnly, "integrators", {0.01, 0.1}, 3.0);
    EXPECT_EQ(study::findings(exactOnly, result).find("with `reflect`"), std::string::npos);
}

// The shadow energy and the mirror's gain explain a bounce under gravity alone; in the README's
// first scene the dryer throws the ball and the floor takes a fifth of each bounce's energy, so
// the findings give the figures, less the dryer's work, and no cause they have not measured.
TEST(IntegratorFindings, TheBounceMechanismsAreNamedOnlyWhereGravityAloneActs)
{
    study::StudyConfig config;
    config.scene = loadScene((sourceDir() / "docs/examples/first-scene.json").string());
    config.dts = {0.01, 0.05, 0.1};
    config.duration = 5.0;
    config.jobs = 2;
    const auto result = study::runStudy(config);
    ASSERT_TRUE(study::anyCollision(result));
    const std::string text = study::findings(config, result);
    expectEverySentenceMeaningful(text);
    EXPECT_EQ(text.find("shadow energy"), std::string::npos) << text;
    EXPECT_EQ(text.find("The mirror adds it"), std::string::npos) << text;
    EXPECT_NE(text.find("**Semi-implicit Euler.** With the `exact` response its energy less the dryer's work after 5 s"),
              std::string::npos)
        << text;
}

// Where no exact solution speaks (the README's first scene, a ball in a dryer's jet), the four
// methods are set side by side by the largest dt each keeps the energy within 1% at, with every
// response and every smaller dt (docs/compare.md quotes these); the table's own figures are the
// oracle. A scene with an exact solution has its own findings and not this one.
TEST(IntegratorFindings, WithoutAnExactSolutionTheMethodsAreComparedByTheStepThatKeepsTheEnergy)
{
    study::StudyConfig config;
    config.scene = loadScene((sourceDir() / "docs/examples/first-scene.json").string());
    config.dts = {0.001, 0.002, 0.005, 0.01, 0.02};
    config.jobs = 2;
    const auto result = study::runStudy(config);
    const std::string text = study::findings(config, result);
    expectEverySentenceMeaningful(text);
    EXPECT_NE(text.find("**The largest step that keeps the energy.** Within 1% of the start after 10 s (less the "
                        "dryer's work), with every response: forward-euler up to dt = 0.002; semi-implicit-euler and "
                        "velocity-verlet up to dt = 0.005; rk4 up to dt = 0.01."),
              std::string::npos)
        << text;
    for (const Integrator m : config.integrators)
        for (const CollisionResponse c : config.collisions)
            for (const double dt : config.dts) {
                const double kept = m == Integrator::ForwardEuler ? 0.002 : m == Integrator::RK4 ? 0.01 : 0.005;
                const auto* run = study::findRun(result, m, c, dt);
                ASSERT_NE(run, nullptr);
                if (dt <= kept) {
                    EXPECT_NEAR(run->energyRatioEnd, 1.0, 0.01) << integratorName(m) << " " << dt;
                }
            }

    study::StudyConfig bounce;
    const auto exact = shortStudy(bounce, "integrators", {0.001, 0.002}, 2.0);
    EXPECT_EQ(study::findings(bounce, exact).find("The largest step"), std::string::npos);
}

TEST(IntegratorFindings, NothingCollidesOnTheSpringSoOneResponseStandsForAll)
{
    study::StudyConfig config;
    const auto result = shortStudy(config, "spring", {0.005, 0.01, 0.02}, 2.0);
    EXPECT_FALSE(study::anyCollision(result));
    EXPECT_EQ(study::distinctResponses(config, result).size(), 1u);
    const std::string text = study::findings(config, result);
    expectEverySentenceMeaningful(text);
    EXPECT_NE(text.find("**Nothing collides.**"), std::string::npos) << text;
    std::size_t mentions = 0;
    for (std::size_t at = text.find("response"); at != std::string::npos; at = text.find("response", at + 1))
        ++mentions;
    EXPECT_EQ(mentions, 1u) << "only the sentence that says they are alike names the responses:\n" << text;

    const auto dir = freshDir("spring_plots");
    const std::string script = study::plotScript(dir, config, result);
    EXPECT_EQ(script.find("collision response"), std::string::npos) << script;
    EXPECT_EQ(script.find("exact response"), std::string::npos) << script;
    EXPECT_NE(script.find("set multiplot layout 1,1 title 'energy"), std::string::npos) << script;
}

// Semi-implicit Euler is symplectic only below its stability limit (2 / omega = 0.0667 s on the
// stiff spring): a dt above it is reported apart, growing without bound, and never as a swing.
TEST(IntegratorFindings, SemiImplicitEulerAboveItsStabilityLimitIsNotCalledSymplectic)
{
    study::StudyConfig config;
    config.integrators = {Integrator::SemiImplicitEuler};
    const auto result = shortStudy(config, "stiff-spring", {0.01, 0.05, 0.1}, 5.0);
    const std::string text = study::findings(config, result);
    expectEverySentenceMeaningful(text);
    const std::size_t swing = text.find("its error swings but does not grow");
    const std::size_t above = text.find("Above its stability limit (dt = 0.06");
    ASSERT_NE(swing, std::string::npos) << text;
    ASSERT_NE(above, std::string::npos) << text;
    const std::string stable = text.substr(0, swing), unstable = text.substr(above);
    EXPECT_NE(stable.find("at dt = 0.01 and"), std::string::npos) << text;
    EXPECT_NE(stable.find("at dt = 0.05"), std::string::npos) << text;
    EXPECT_EQ(stable.find("dt = 0.1"), std::string::npos) << text;
    EXPECT_NE(unstable.find("its energy grows without bound"), std::string::npos) << text;
    // A run that blew up has no end energy to quote (it would read "inf"): when it blew up instead.
    EXPECT_NE(unstable.find("it blew up at t = 0.2 s at dt = 0.1"), std::string::npos) << text;
    EXPECT_EQ(text.find("inf"), std::string::npos) << text;

    // Every dt below the limit: the one sentence, as before.
    study::StudyConfig below;
    below.integrators = {Integrator::SemiImplicitEuler};
    const std::string belowText = study::findings(below, shortStudy(below, "stiff-spring", {0.01, 0.02}, 5.0));
    EXPECT_NE(belowText.find("its error swings but does not grow"), std::string::npos) << belowText;
    EXPECT_EQ(belowText.find("Above its stability limit"), std::string::npos) << belowText;
}

TEST(IntegratorPlots, EachIntegratorsLineIsInItsPaletteColour)
{
    study::StudyConfig config;
    config.scene = loadScene("integrators");
    const auto dir = freshDir("palette_plots");
    const std::string script = study::plotScript(dir, config, defaultStudy());
    // One section per picture, from its `set output` to the next.
    for (const char* picture : study::kPlotFiles) {
        const std::size_t begin = script.find(std::string("set output '") + picture + "'");
        ASSERT_NE(begin, std::string::npos) << picture;
        const std::string section = script.substr(begin, script.find("set output", begin + 1) - begin);
        for (Integrator integrator : kAllIntegrators) {
            const std::string colour = "lc rgb '" + palette::hex(palette::integratorRgb(integrator)) + "'";
            EXPECT_NE(section.find(colour), std::string::npos) << picture << ": " << integratorName(integrator);
        }
        // No line left to gnuplot's default colours.
        std::istringstream lines(section);
        for (std::string line; std::getline(lines, line);)
            for (std::size_t at = line.find("with line"); at != std::string::npos; at = line.find("with line", at + 1))
                EXPECT_NE(line.substr(at, line.find(", ", at) - at).find("lc rgb"), std::string::npos) << line;
    }
    EXPECT_EQ(palette::hex(palette::kForwardEuler), "#ed5445");
}

TEST(IntegratorPlots, PanelsFitTheNumberOfIntegrators)
{
    study::StudyConfig config;
    config.integrators = {Integrator::RK4, Integrator::VelocityVerlet};
    const auto result = shortStudy(config, "integrators", {0.01}, 2.0);
    const std::string script = study::plotScript(freshDir("two_panels"), config, result);
    EXPECT_NE(script.find("set multiplot layout 1,2 title 'height"), std::string::npos) << script;
}

// On a scene with rigid bodies `pba compare` studies rotation: a row per integrator and dt, the
// drift and flip plots, the period's plot where the exact period is known; --collisions is
// refused there (rigid bodies have no collision responses to compare).
TEST(PbaCompare, RigidSceneGetsTheRotationStudy)
{
    const auto dir = freshDir("compare-rigid");
    const CommandResult r = runPba("compare tennis-racket --duration 7 --dt 0.002,0.01 --out " + (dir / "racket").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("flip period error"), std::string::npos) << r.out;
    std::istringstream csv(readFile(dir / "racket/results.csv"));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "integrator,dt,body,steps,energy_ratio_end,max_energy_drift,max_momentum_drift,flips,flip_period,"
                    "exact_period,blew_up_at");
    int rows = 0;
    while (std::getline(csv, line))
        ++rows;
    EXPECT_EQ(rows, 12); // the six rigid integrators (splitting among them), two dt
    for (const char* picture : {"drift.png", "flip.png", "period.png"}) {
        int w = 0, h = 0, channels = 0;
        stbi_uc* pixels = stbi_load((dir / "racket" / picture).string().c_str(), &w, &h, &channels, 3);
        EXPECT_NE(pixels, nullptr) << picture;
        EXPECT_GT(w, 600) << picture;
        stbi_image_free(pixels);
    }
    EXPECT_NE(readFile(dir / "racket/report.md").find("T_exact = 5.86"), std::string::npos);
    // The runs are independent: the same files whatever --jobs is.
    const CommandResult one = runPba("compare tennis-racket --duration 7 --dt 0.002,0.01 --jobs 1 --out " +
                                     (dir / "one").string());
    ASSERT_EQ(one.exitCode, 0) << one.err;
    for (const char* file : {"results.csv", "report.md"})
        EXPECT_EQ(readFile(dir / "racket" / file), readFile(dir / "one" / file)) << file;
    EXPECT_EQ(runPba("compare dice --collisions exact --out " + (dir / "dice").string()).exitCode, 2);
    EXPECT_FALSE(std::filesystem::exists(dir / "dice"));
}

// --body picks the rigid body the rotation study measures. One that touches the room or a ramp
// is said to be no free body, so its drift is not read as its method's; a name that is no moving
// rigid body is bad input, and nothing is written.
TEST(PbaCompare, TheRotationStudyMeasuresTheBodyNamedAndSaysWhenItIsNoFreeBody)
{
    const auto dir = freshDir("compare-body");
    const CommandResult r = runPba("compare incline --body steep-box --duration 1 --dt 0.01 --out " +
                                   (dir / "incline").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string report = readFile(dir / "incline/report.md");
    EXPECT_NE(report.find("following the rigid body `steep-box`"), std::string::npos) << report;
    EXPECT_NE(report.find("`steep-box` is no free body here (it touches other bodies or the room)"), std::string::npos)
        << report;
    EXPECT_NE(report.find("`steep-box` starts without spin: it has no |L| to keep"), std::string::npos) << report;
    EXPECT_NE(report.find("| forward-euler | no spin |"), std::string::npos) << report;
    const CommandResult racket = runPba("compare tennis-racket --duration 1 --dt 0.01 --out " + (dir / "racket").string());
    ASSERT_EQ(racket.exitCode, 0) << racket.err;
    EXPECT_EQ(readFile(dir / "racket/report.md").find("no free body"), std::string::npos);
    const std::pair<const char*, const char*> bad[] = {
        {"incline --body steepbox", "--body: builtin:incline has no body named 'steepbox': did you mean 'steep-box'?"},
        {"incline --body steep-ramp", "--body: 'steep-ramp' in builtin:incline is fixed"},
        {"spring --body bob", "--body: chooses the rigid body the rotation study measures, and builtin:spring has no "
                              "moving rigid body"},
        {"tennis-racket --work-precision", "--work-precision: goes with the integrator study, and builtin:tennis-racket "
                                           "has a moving rigid body"}};
    for (const auto& [args, message] : bad) {
        const CommandResult e = runPba(std::string("compare ") + args + " --out " + (dir / "bad").string());
        EXPECT_EQ(e.exitCode, 2) << args;
        EXPECT_NE(e.err.find(message), std::string::npos) << e.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "bad")) << args;
    }
}

// A run that blows up is a result of the study, not its end. The rope with springs of stiffness
// 1e300 stays finite in the closed room, but its energy leaps in the first step: every particle's
// row says it blew up then (BlowUpWatch), and no energy ratio is read from a blown-up run.
TEST(IntegratorStudy, ARunWhoseEnergyExplodesInsideTheRoomIsRecordedAsBlownUp)
{
    std::string json(builtinSceneText("rope"));
    json.replace(json.find("\"stiffness\": 500"), 16, "\"stiffness\": 1e300");
    const Scene scene = parseScene(json, "rope.json");
    const auto runs = study::measureRun(scene, Integrator::SemiImplicitEuler, CollisionResponse::Exact, 0.002, 0.1);
    ASSERT_EQ(runs.size(), 24u); // the moving particles
    for (const auto& r : runs) {
        EXPECT_DOUBLE_EQ(r.blewUpAt, 0.002) << r.particle;
        EXPECT_TRUE(std::isinf(r.energyRatioEnd)) << r.particle;
    }
}

// In a scene with a blow dryer the study's energies are the bodies' less the dryer's work, so
// its ratios are the integration's: the practical's ball, thrown into the jet and hovering there
// 60 s later (its raw ratio is 1.76: the dryer lifted it), and the report's tables say so. Its
// forward and semi-implicit Euler runs are discrete oracles: the dryer's work is exactly the
// kinetic energy it gave, and gravity's steps telescope to m g dt (vy(0) - vy(end)) / 2 of energy
// gained (forward Euler moves with the start's velocity) or lost (semi-implicit with the end's),
// the ball thrown up at 4 m/s and at rest at the end. Velocity Verlet and RK4 keep it within 0.1%.
TEST(IntegratorStudy, InTheDryerTheEnergyIsTheIntegrationsWithoutTheDryersWork)
{
    const Scene scene = loadScene("blow-dryer");
    const double dt = 0.001, e0 = scene.world.totalEnergy(), vy = scene.world.body(0).getVel().y;
    for (const Integrator integrator : kAllIntegrators) {
        const auto runs = study::measureRun(scene, integrator, CollisionResponse::Reflect, dt, 60.0);
        ASSERT_EQ(runs.size(), 1u);
        ASSERT_EQ(runs[0].bounces, 0u);
        const double telescoped = 9.81 * dt * vy / (2.0 * e0);
        if (integrator == Integrator::ForwardEuler)
            EXPECT_NEAR(runs[0].energyRatioEnd, 1.0 + telescoped, 1e-9);
        else if (integrator == Integrator::SemiImplicitEuler)
            EXPECT_NEAR(runs[0].energyRatioEnd, 1.0 - telescoped, 1e-9);
        else
            EXPECT_NEAR(runs[0].energyRatioEnd, 1.0, 1e-3) << integratorName(integrator);
    }
    const auto dir = freshDir("compare-dryer");
    const CompareRun run = runCompare("blow-dryer --dt 0.001,0.002 --duration 2", dir);
    ASSERT_TRUE(run.ok()) << run.result.err;
    EXPECT_NE(run.report.find("Energy at the end over energy at the start (less the dryer's work)"), std::string::npos)
        << run.report;
}

// `pba compare` on the dryer's boxes with the lightest of a picogram used to stop at its first
// run with exit 1 ("an orientation must be a non-zero finite quaternion"), writing nothing. Now
// every run that blows up has its time in blew_up_at, and the study goes on to its report.
TEST(PbaCompare, ARigidRunThatBlowsUpIsRecordedAndTheStudyGoesOn)
{
    const auto dir = freshDir("compare-blow-up");
    std::string json(builtinSceneText("blow-dryer-boxes"));
    json.replace(json.find("\"mass\": 0.5"), 11, "\"mass\": 1e-12");
    std::ofstream(dir / "boxes.json") << json;
    const CommandResult r = runPba("compare " + (dir / "boxes.json").string() + " --dt 0.002,0.01 --duration 0.2 --out " +
                                   (dir / "study").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::istringstream csv(readFile(dir / "study/results.csv"));
    std::string line;
    std::getline(csv, line);
    ASSERT_EQ(line.substr(line.rfind(',') + 1), "blew_up_at");
    int rows = 0, blown = 0;
    while (std::getline(csv, line)) {
        ++rows;
        const std::string last = line.substr(line.rfind(',') + 1);
        EXPECT_EQ(line.rfind(',', line.size()), line.rfind(',')) << line;
        if (!last.empty() && last != "nan" && std::isfinite(std::stod(last))) {
            ++blown;
            EXPECT_GT(std::stod(last), 0.0) << line;
            EXPECT_LE(std::stod(last), 0.2) << line;
        }
    }
    EXPECT_EQ(rows, 12); // the six rigid integrators (splitting among them), two dt
    EXPECT_GT(blown, 0);
    EXPECT_TRUE(std::filesystem::exists(dir / "study/report.md"));
}

// Work against precision (--work-precision): work_precision.csv has every scene and method that did not blow up,
// the report its section and picture, and the spring's points have the methods' orders: halving
// dt divides RK4's error by about 16, backward Euler's and XPBD's by about 2.
TEST(PbaCompare, WritesWorkPrecisionWithTheMethodsOrders)
{
    const auto dir = freshDir("compare-work-precision");
    const CommandResult r = runPba("compare --duration 1 --dt 0.01,0.02 --integrators semi-implicit-euler "
                                   "--collisions reflect --work-precision --out " + (dir / "out").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto rows = csvRows(dir / "out/work_precision.csv");
    ASSERT_FALSE(rows.empty());
    EXPECT_EQ(rows[0], (std::vector<std::string>{"scene", "integrator", "dt", "error", "cpu_s"}));
    std::map<std::string, double> error; // "scene integrator dt"
    std::set<std::string> scenes;
    for (std::size_t row = 1; row < rows.size(); ++row) {
        const std::vector<std::string>& cells = rows[row];
        ASSERT_EQ(cells.size(), 5u) << "row " << row;
        scenes.insert(cells[0]);
        EXPECT_GT(std::stod(cells[4]), 0.0) << cells[0];
        error[cells[0] + " " + cells[1] + " " + cells[2]] = std::stod(cells[3]);
    }
    EXPECT_EQ(scenes, (std::set<std::string>{"spring", "chain", "cloth", "tennis-racket"}));
    const auto ratio = [&](const std::string& method) {
        return error.at("spring " + method + " 0.001") / error.at("spring " + method + " 0.002");
    };
    EXPECT_NEAR(std::log2(ratio("rk4")), -4.0, 0.5);
    EXPECT_NEAR(std::log2(ratio("implicit-euler")), -1.0, 0.3);
    EXPECT_NEAR(std::log2(ratio("xpbd")), -1.0, 0.3);
    // The chain, measured before its free end strikes the wall at 0.85 s: its error falls with dt
    // (semi-implicit Euler's order one: a quarter at a quarter of dt), where at 1 s, after the
    // impacts, it read 0.2 to 0.3 m at every dt.
    for (const char* method : {"semi-implicit-euler", "splitting"}) {
        const double fine = error.at(std::string("chain ") + method + " 0.0005");
        const double coarse = error.at(std::string("chain ") + method + " 0.002");
        EXPECT_LT(std::log2(fine / coarse), -1.5) << method;
        EXPECT_LT(fine, 0.01) << method;
    }
    const std::string report = readFile(dir / "out/report.md");
    EXPECT_NE(report.find("## Work against precision"), std::string::npos);
    EXPECT_NE(r.out.find("work against precision"), std::string::npos);
}

namespace {

std::optional<pba::study::ExactSolution> exactOfFirst(const std::string& json)
{
    const pba::Scene scene = pba::parseScene(json, "exact.json");
    return pba::study::ExactSolution::find(scene.world, 0);
}

} // namespace

// An exact solution is claimed only for the motion it describes: a point dropped from above the
// floor, or on a spring that never reaches its anchor, alone. A ball (the floor meets it a radius
// up, and other balls meet it), a particle a joint holds, one lying on the floor (no bounce, a
// period of 0) and a spring passed through its anchor (no longer linear) have none.
TEST(ExactSolutions, OnlyAPointMovingAloneHasOne)
{
    const std::string drop = R"({"ground": {"height": 0}, "particles": [{"name": "p", "position": [0, 1, 0])";
    EXPECT_TRUE(exactOfFirst(drop + "}]}").has_value());
    EXPECT_FALSE(exactOfFirst(drop + R"(, "radius": 0.1}]})").has_value());
    EXPECT_FALSE(exactOfFirst(R"({"ground": {"height": 0}, "particles": [{"name": "p", "position": [0, 0, 0]}]})")
                     .has_value());
    EXPECT_FALSE(exactOfFirst(R"({"ground": {"height": 0}, "particles": [{"name": "p", "position": [1, 2, 0]}],
        "rigid_bodies": [{"name": "post", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "position": [0, 3, 0],
                          "fixed": true}],
        "joints": [{"type": "distance", "bodies": ["p", "post"], "anchors": [[1, 2, 0], [0, 3, 0]]}]})")
                     .has_value());
    const std::string spring = R"({"gravity": [0, 0, 0], "particles": [{"name": "p", "position": [0, 1, 0],
        "velocity": [0, VY, 0]}], "forces": [{"type": "spring", "particle": "p", "anchor": [0, 0, 0], "stiffness": 10,
        "rest_length": 1}]})";
    const auto withSpeed = [&](const char* vy) {
        std::string s = spring;
        s.replace(s.find("VY"), 2, vy);
        return exactOfFirst(s);
    };
    EXPECT_TRUE(withSpeed("1").has_value()) << "amplitude 0.32 m of a 1 m spring";
    EXPECT_FALSE(withSpeed("-20").has_value()) << "amplitude 6.3 m: through the anchor";
}
