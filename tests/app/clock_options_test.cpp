// pba view's and pba render's --clock and render's --no-interpolation: each clock draws its own
// picture, interpolation changes what is drawn between steps, and a bad clock is a usage error.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "support/run_command.hpp"

using namespace pba::test;

namespace {

std::string bytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

TEST(RenderClock, EachClockDrawsItsOwnRunAndTheFixedOneIsTheDefault)
{
    const auto dir = freshDir("render-clock");
    const std::string common = "render stiff-spring --size 96x64 --time 1.3 --out ";
    for (const char* clock : {"", "fixed", "semi-fixed", "variable"}) {
        const std::string name = std::string(*clock ? clock : "default") + ".png";
        const auto r = runPba(common + (dir / name).string() + (*clock ? std::string(" --clock ") + clock : ""));
        ASSERT_EQ(r.exitCode, 0) << clock << r.err;
    }
    EXPECT_EQ(bytes(dir / "default.png"), bytes(dir / "fixed.png"));
    EXPECT_NE(bytes(dir / "fixed.png"), bytes(dir / "variable.png"));
    EXPECT_NE(bytes(dir / "fixed.png"), bytes(dir / "semi-fixed.png"));
}

TEST(RenderClock, NoInterpolationDrawsTheLastStateBetweenSteps)
{
    const auto dir = freshDir("render-interpolation");
    const std::string common = "render stiff-spring --size 96x64 --time 1.305 --out ";
    ASSERT_EQ(runPba(common + (dir / "blended.png").string()).exitCode, 0);
    ASSERT_EQ(runPba(common + (dir / "last.png").string() + " --no-interpolation").exitCode, 0);
    EXPECT_NE(bytes(dir / "blended.png"), bytes(dir / "last.png"));
}

TEST(RenderClock, AnUnknownClockIsAUsageErrorInViewAndRender)
{
    const auto dir = freshDir("render-clock-bad");
    for (const std::string& command : {"render stiff-spring --out " + (dir / "x.png").string(), std::string("view")}) {
        const auto r = runPba(command + " --clock sometimes");
        EXPECT_EQ(r.exitCode, 2) << command;
        EXPECT_NE(r.err.find("--clock: unknown clock 'sometimes'"), std::string::npos) << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}
