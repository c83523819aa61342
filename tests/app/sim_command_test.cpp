// `pba sim` end to end: the CSV contract, frame-rate independence and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "support/run_command.hpp"

using namespace pba::test;

TEST(PbaSim, PrintsASummaryTableForTheIntegratorsScene)
{
    const CommandResult r = runPba("sim integrators");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* expected : {"reference", "forward-euler", "semi-implicit-euler", "highest y", "bounces",
                                 "E now/E start"})
        EXPECT_NE(r.out.find(expected), std::string::npos) << expected << "\n" << r.out;
}

TEST(PbaSim, WritesOneCsvRowPerBodyPerStepIncludingStepZero)
{
    const auto dir = freshDir("sim_csv");
    const auto csv = dir / "run.csv";
    const CommandResult r = runPba("sim integrators --dt 0.01 --duration 1 --out " + csv.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header.rfind("step,t,body,x,y,z,vx,vy,vz", 0), 0u) << header;
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line.rfind("0,0,reference,", 0), 0u) << line;
    int rows = 1;
    std::string last;
    while (std::getline(in, line)) {
        ++rows;
        last = line;
    }
    EXPECT_EQ(rows, 101 * 3);
    EXPECT_EQ(last.rfind("100,1,semi-implicit-euler,", 0), 0u) << last;
}

TEST(PbaSim, FrameRateDoesNotChangeTheResults)
{
    const auto dir = freshDir("sim_frames");
    for (const char* rate : {"30", "144"}) {
        const CommandResult r = runPba(std::string("sim integrators --duration 3 --frame-rate ") + rate + " --out " +
                                       (dir / (std::string(rate) + ".csv")).string());
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    const CommandResult plain = runPba("sim integrators --duration 3 --out " + (dir / "plain.csv").string());
    ASSERT_EQ(plain.exitCode, 0);
    const std::string a = readFile(dir / "30.csv");
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, readFile(dir / "144.csv"));
    EXPECT_EQ(a, readFile(dir / "plain.csv"));
}

TEST(PbaSim, OverridesApplyToEveryMovingParticle)
{
    const CommandResult r = runPba("sim integrators --integrator rk4 --collision reflect --dt 0.005 --duration 2");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("collision response reflect"), std::string::npos);
    EXPECT_NE(r.out.find("(fixed)"), std::string::npos);
    EXPECT_EQ(r.out.find("forward-euler          forward-euler"), std::string::npos);
}

struct BadRun {
    const char* args;
    const char* message;
};

void PrintTo(const BadRun& bad, std::ostream* os) { *os << bad.args; }

class PbaSimBadInput : public testing::TestWithParam<BadRun> {};

TEST_P(PbaSimBadInput, ExitsTwoWithOneLineAndNoOutputFile)
{
    const auto dir = freshDir("sim_bad");
    const auto scene = dir / "bad.json";
    std::ofstream(scene) << R"({"particles": [{"name": "a", "position": [0, 1, 0], "mass": -1}]})";
    std::string args = GetParam().args;
    if (const auto pos = args.find("BAD"); pos != std::string::npos)
        args.replace(pos, 3, scene.string());
    const auto out = dir / "out.csv";
    const CommandResult r = runPba("sim " + args + " --out " + out.string());
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1) << "no temporary files left";
}

INSTANTIATE_TEST_SUITE_P(
    PbaSim, PbaSimBadInput,
    testing::Values(BadRun{"BAD", "particles[0].mass: must be positive"},
                    BadRun{"no-such-scene", "neither a built-in scene"},
                    BadRun{"/nonexistent/x.json", "no such file"},
                    BadRun{"integrators --dt 0", "--dt: must be finite and positive"},
                    BadRun{"integrators --dt -1", "--dt"},
                    BadRun{"integrators --duration 0", "--duration"},
                    BadRun{"integrators --integrator leapfrog", "unknown integrator 'leapfrog'"},
                    BadRun{"integrators --collision bounce", "unknown collision response 'bounce'"},
                    BadRun{"integrators --frame-rate 0", "--frame-rate"},
                    BadRun{"integrators --no-such-option", "no-such-option"},
                    BadRun{"integrators --dt abc", "--dt: cannot read 'abc' as a number"},
                    BadRun{"integrators --duration 1,5", "--duration: cannot read '1,5' as a number"}));

// A mistyped command is named, with the command it is close to, in the order it was typed.
TEST(PbaCommands, AMistypedCommandIsNamedWithTheOneItIsCloseTo)
{
    CommandResult r = runPba("simm integrators");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "pba: error: unknown command 'simm': did you mean 'sim'? (the commands: sim, field, render, view, "
                     "compare, bench, scenes, help)\n");
    r = runPba("frobnicate");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("unknown command 'frobnicate' (the commands: sim,"), std::string::npos) << r.err;
}

// The issue's two typos, as a student meets them: one line on stderr naming the file, the key
// and the key it is close to, exit 2.
TEST(PbaSim, AMisspeltSceneKeyIsNamedWithTheKeyItIsCloseTo)
{
    const auto dir = freshDir("sim_typo");
    const std::string spring = R"("forces": [{"type": "spring", "particle": "b", "anchor": [0, 2, 0], )";
    std::ofstream(dir / "partcles.json") << R"({"partcles": [{"name": "b", "position": [0, 1, 0]}], )" << spring
                                         << R"("stiffness": 1}]})";
    std::ofstream(dir / "stifness.json") << R"({"particles": [{"name": "b", "position": [0, 1, 0]}], )" << spring
                                         << R"("stifness": 1}]})";
    CommandResult r = runPba("sim " + (dir / "partcles.json").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "pba: error: " + (dir / "partcles.json").string() +
                         ": partcles: unknown key (did you mean \"particles\"?)\n");
    r = runPba("sim " + (dir / "stifness.json").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "pba: error: " + (dir / "stifness.json").string() +
                         ": forces[0].stifness: unknown key (did you mean \"stiffness\"?)\n");
}

TEST(PbaSim, ABadClothOrRopeIsExit2NamingTheField)
{
    const auto dir = freshDir("sim_bad_fabric");
    const std::string room = R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, )";
    std::ofstream(dir / "corner.json") << room << R"("cloths": [{"name": "c", "origin": [-1, 3, -1], )"
                                       << R"("across": [2, 0, 0], "down": [0, 0, 2], "columns": 4, "rows": 4, )"
                                       << R"("stiffness": {"structural": 10}, "pinned": ["top-centre"]}]})";
    std::ofstream(dir / "count.json") << room << R"("ropes": [{"name": "r", "from": [-1, 3, 0], "to": [1, 3, 0], )"
                                      << R"("count": 1, "stiffness": 10}]})";
    CommandResult r = runPba("sim " + (dir / "corner.json").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find(": cloths[0].pinned: unknown corner 'top-centre'"), std::string::npos) << r.err;
    r = runPba("sim " + (dir / "count.json").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find(": ropes[0].count: must be a whole number from 2"), std::string::npos) << r.err;
}

TEST(PbaSim, UnwritableOutputIsBadInput)
{
    const CommandResult r = runPba("sim integrators --out /nonexistent/dir/run.csv");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("/nonexistent/dir/run.csv"), std::string::npos) << r.err;
}

TEST(PbaSim, HelpExplainsEveryOption)
{
    const CommandResult top = runPba("--help");
    EXPECT_EQ(top.exitCode, 0);
    EXPECT_NE(top.out.find("sim"), std::string::npos);
    const CommandResult sim = runPba("sim --help");
    EXPECT_EQ(sim.exitCode, 0);
    for (const char* option : {"--dt", "--duration", "--integrator", "--collision", "--frame-rate", "--out"})
        EXPECT_NE(sim.out.find(option), std::string::npos) << option;
}

// A position outside the room is told the room's bounds (or the ground's height), so the fix
// can be read off the message.
TEST(PbaSim, APositionOutsideTheRoomIsToldItsBounds)
{
    const auto dir = freshDir("sim_outside");
    std::ofstream(dir / "room.json") << R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]},
        "particles": [{"name": "a", "position": [0, 5, 0]}]})";
    std::ofstream(dir / "ground.json") << R"({"ground": {"height": 0.5}, "ropes": [{"name": "r", "from": [0, 1, 0],
        "to": [2, 0, 0], "count": 3, "stiffness": 10}]})";
    CommandResult r = runPba("sim " + (dir / "room.json").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("particles[0].position: (0, 5, 0) lies outside the ground or room: the room spans x -2 to 2, "
                         "y 0 to 4, z -2 to 2 m\n"),
              std::string::npos)
        << r.err;
    r = runPba("sim " + (dir / "ground.json").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("ropes[0].to: particle 'r[2]' at (2, 0, 0) lies outside the ground or room: the ground is at "
                         "y = 0.5 m\n"),
              std::string::npos)
        << r.err;
}
