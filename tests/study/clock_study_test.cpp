// The clocks study (`pba compare --clocks`): the fixed clock's runs agree to the bit at every
// frame rate, the variable clock's do not, and the hitch is one step of a quarter second.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <sstream>

#include "pba/scene/scene.hpp"
#include "study/clock_study.hpp"
#include "support/run_command.hpp"

using namespace pba;
using namespace pba::study;

namespace {

ClockResult runScene(const std::string& scene, double duration)
{
    ClockConfig config;
    config.scene = loadScene(scene);
    config.dt = config.scene.dt;
    config.duration = duration;
    return runClockStudy(config);
}

const ClockDrift& drift(const ClockResult& r, ClockKind clock, bool hitch, int rate)
{
    for (const ClockDrift& d : r.drifts)
        if (d.clock == clock && d.hitch == hitch && d.rate == rate)
            return d;
    throw std::logic_error("no such drift");
}

} // namespace

TEST(ClockStudy, FixedIsIdenticalToTheBitAtEveryRateAndVariableIsNot)
{
    const ClockResult r = runScene("integrators", 3.0);
    ASSERT_EQ(r.runs.size(), 3u * 2u * 3u);
    ASSERT_EQ(r.drifts.size(), 3u * 2u * 2u);
    for (const bool hitch : {false, true})
        for (const int rate : {30, 144}) {
            const ClockDrift& fixed = drift(r, ClockKind::Fixed, hitch, rate);
            EXPECT_TRUE(fixed.identical) << rate;
            EXPECT_EQ(fixed.maxDistance, 0.0);
            EXPECT_GE(fixed.t.size(), 10u); // the shared frames were sampled
            EXPECT_FALSE(drift(r, ClockKind::Variable, hitch, rate).identical) << rate;
            EXPECT_GT(drift(r, ClockKind::Variable, hitch, rate).maxDistance, 1e-3) << rate;
            EXPECT_FALSE(drift(r, ClockKind::SemiFixed, hitch, rate).identical) << rate;
        }
}

// The fixed clock takes floor(t / dt) steps by the last frame's end t at every frame rate: 300
// in 3 s at dt = 0.01 s, or 298 at 30 Hz with the hitch, whose frames end at 2.9833 s (0.25 s is
// the clamp, so no time is dropped). A sum of frame times that rounds below a step still takes
// it, and every shared frame, those on a step of dt included, compares equal.
TEST(ClockStudy, TheFixedClockTakesExactlyTheExpectedStepsAtEveryRate)
{
    const ClockResult r = runScene("integrators", 3.0);
    for (const ClockRun& run : r.runs)
        if (run.clock == ClockKind::Fixed) {
            // The last frame's end, the sum of the frame times.
            const std::vector<double> frames = frameTimes(run.rate, run.hitch, 3.0);
            const double end = std::accumulate(frames.begin(), frames.end(), 0.0);
            const auto expected = static_cast<std::uint64_t>(std::floor(end / 0.01 + 1e-6));
            EXPECT_EQ(run.steps, expected) << run.rate << " Hz" << (run.hitch ? ", hitch" : "");
            EXPECT_EQ(run.steps, run.hitch && run.rate == 30 ? 298u : 300u) << run.rate << " Hz";
        }
    for (const bool hitch : {false, true})
        for (const int rate : {30, 144}) {
            const ClockDrift& fixed = drift(r, ClockKind::Fixed, hitch, rate);
            const auto onAStep = std::count_if(fixed.t.begin(), fixed.t.end(), [](double t) {
                return std::abs(t * 100.0 - std::round(t * 100.0)) < 1e-6;
            });
            EXPECT_GE(onAStep, 4) << rate << (hitch ? " Hz, hitch" : " Hz");
            EXPECT_TRUE(fixed.identical) << rate;
        }
}

TEST(ClockStudy, TheHitchIsOneLongStepOnlyForTheVariableClock)
{
    const ClockResult r = runScene("integrators", 2.5);
    for (const ClockRun& run : r.runs) {
        // The semi-fixed clock's steps are never longer than dt, nor than a frame (1/144 s < dt).
        const double frame = 1.0 / run.rate;
        const double longest = run.clock == ClockKind::Variable    ? (run.hitch ? 0.25 : frame)
                               : run.clock == ClockKind::SemiFixed ? (run.hitch ? 0.01 : std::min(0.01, frame))
                                                                   : 0.01;
        EXPECT_NEAR(run.longestStep, longest, 1e-12) << clockName(run.clock) << ' ' << run.rate << ' ' << run.hitch;
    }
}

TEST(ClockStudy, FrameTimesAddUpToTheRunWithTheHitchInside)
{
    for (const int rate : {30, 60, 144}) {
        const std::vector<double> steady = frameTimes(rate, false, 3.0);
        EXPECT_EQ(steady.size(), std::size_t(3 * rate));
        EXPECT_NEAR(std::accumulate(steady.begin(), steady.end(), 0.0), 3.0, 1e-12);
        const std::vector<double> hitched = frameTimes(rate, true, 3.0);
        EXPECT_EQ(std::count(hitched.begin(), hitched.end(), kHitchSeconds), 1) << rate;
        EXPECT_NEAR(std::accumulate(hitched.begin(), hitched.end(), 0.0), 3.0, 1.0 / rate);
    }
}

TEST(ClockStudy, RefusesARunTooShortForTheHitch)
{
    EXPECT_THROW(runScene("integrators", 2.0), std::invalid_argument);
}

TEST(PbaCompareClocks, WritesTheReportTableAndCsv)
{
    const auto dir = pba::test::freshDir("compare-clocks");
    const auto r = pba::test::runPba("compare --clocks integrators --duration 2.5 --out " + (dir / "out").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream in(dir / "out/report.md");
    std::stringstream report;
    report << in.rdbuf();
    EXPECT_NE(report.str().find("## Findings"), std::string::npos);
    EXPECT_NE(report.str().find("| fixed | steady | identical (to the bit) | identical (to the bit) |"), std::string::npos);
    std::ifstream csv(dir / "out/clocks.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header, "clock,hitch,rate,t,distance");
    EXPECT_NE(r.out.find("variable"), std::string::npos);
    // What it wrote is a result, on stdout as every command's "wrote" line.
    EXPECT_NE(r.out.find("wrote " + (dir / "out").string() + "/report.md, clocks.csv"), std::string::npos) << r.out;
    EXPECT_EQ(r.err.find("wrote"), std::string::npos) << r.err;
}

TEST(PbaCompareClocks, RefusesWhatDoesNotApply)
{
    const auto dir = pba::test::freshDir("compare-clocks-bad");
    const std::string out = " --out " + (dir / "out").string();
    for (const std::string args : {"--clocks --integrators rk4", "--clocks --dt 0.01,0.02", "--clocks --duration 1",
                                   "--clocks --body bob", "--clocks --work-precision"}) {
        const auto r = pba::test::runPba("compare integrators " + args + out);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_NE(r.err.find("--"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "out")) << args;
    }
}
