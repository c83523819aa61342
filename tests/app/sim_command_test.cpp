// `pba sim` end to end: the CSV contract, frame-rate independence, bad input, and blow-ups.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pba/scene/scene.hpp"
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
                    BadRun{"integrators --dt 0.01 --dt 0.02", "--dt: given 2 times; give it once"},
                    BadRun{"integrators --dt ''", "--dt: empty; give it a value"},
                    BadRun{"integrators --duration=", "--duration: empty; give it a value"},
                    BadRun{"''", "SCENE: empty; give it a scene name or a file"},
                    BadRun{"--dt 0.01 ''", "SCENE: empty; give it a scene name or a file"},
                    BadRun{"integrators --duration 1,5", "--duration: cannot read '1,5' as a number"},
                    BadRun{"trampoline --integrator xpbd",
                           "has rigid body 'crate' (a rope's or cloth's own \"integrator\" key sets it"},
                    BadRun{"granular --integrator implicit-euler", "has swarm 'grains', which has none"}));

// A CSV under a picture's name would open as a broken picture: refused, nothing written.
TEST(PbaSim, ACsvUnderAPicturesNameIsRefused)
{
    const auto dir = freshDir("sim_out_png");
    const CommandResult r = runPba("sim rope --duration 0.01 --out " + (dir / "run.png").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, fmt::format("pba: error: --out: sim writes CSV, and '{}' names a png file: give a name such as "
                                 "run.csv\n",
                                 (dir / "run.png").string()));
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 0) << "nothing written";
}

// --swarm-particles writes to --out's CSV: alone it would do nothing, so it is refused.
TEST(PbaSim, SwarmParticlesWithoutOutIsRefused)
{
    const CommandResult r = runPba("sim blow-dryer-swarm --swarm-particles --duration 0.01");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "pba: error: --swarm-particles: writes the swarms' particles to --out's CSV, and there is no "
                     "--out\n");
    EXPECT_EQ(r.out, "");
}

// A run takes round(duration / dt) steps, at least one (docs/scenes.md): where that is not the
// duration, the first line says so, and only there.
TEST(PbaSim, SaysWhenTheDurationIsNotAWholeNumberOfSteps)
{
    CommandResult r = runPba("sim integrators --dt 0.3 --duration 1");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.rfind("scene integrators: 3 steps of dt = 0.3 s, t = 0.9 s (the duration, 1 s, is 3.33333 steps: "
                          "a run takes the nearest whole number, at least one), collision response reflect\n", 0),
              0u)
        << r.out;
    r = runPba("sim integrators --dt 0.5 --duration 0.2");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.rfind("scene integrators: 1 step of dt = 0.5 s, t = 0.5 s (the duration, 0.2 s, is 0.4 steps", 0),
              0u)
        << r.out;
    r = runPba("sim integrators --duration 1");
    EXPECT_EQ(r.out.rfind("scene integrators: 100 steps of dt = 0.01 s, t = 1 s, collision", 0), 0u) << r.out;
}

// A mistyped command or option is named, with the one it is close to, in the order it was typed;
// an option of another command (render's --time) is named alone, not with the arguments
// reversed after it. A word past the command's arguments is named with the command, and
// `pba help` names a mistyped command as `pba` does.
TEST(PbaCommands, AMistypedCommandOrOptionIsNamedWithTheOneItIsCloseTo)
{
    const std::pair<const char*, const char*> cases[] = {
        {"simm integrators", "unknown command 'simm': did you mean 'sim'? (the commands: sim, field, render, view, "
                             "compare, bench, scenes, help)"},
        {"help simm", "help: unknown command 'simm': did you mean 'sim'? (the commands: sim, field, render, view, "
                      "compare, bench, scenes, help)"},
        {"sim integrators --dtt 0.1",
         "unknown option '--dtt' of `pba sim`: did you mean '--dt'? (`pba sim --help` lists its options)"},
        {"sim integrators --time 1", "unknown option '--time' of `pba sim` (`pba sim --help` lists its options)"},
        {"sim integrators extra more",
         "unexpected argument 'extra' of `pba sim` (`pba sim --help` lists its arguments)"},
        {"scenes extra", "unexpected argument 'extra' of `pba scenes` (`pba scenes --help` lists its arguments)"},
        // Before the command, an option is root's: CLI11 said "The following argument was not expected".
        {"--bogus sim", "unknown option '--bogus' of `pba` (`pba --help` lists its options)"}};
    for (const auto& [args, message] : cases) {
        const CommandResult r = runPba(args);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(r.err, std::string("pba: error: ") + message + "\n");
    }
    const CommandResult r = runPba("frobnicate");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("unknown command 'frobnicate' (the commands: sim,"), std::string::npos) << r.err;
}

// CLI11's own messages ("--out: 1 required FILE.csv missing", "--windows: Value 0 not in range 1
// to 100") reached the user as CLI11 wrote them: each is one line in pba's form, naming the option
// and the reason, with exit 2.
TEST(PbaCommands, CommandLineErrorsNameTheOptionAndTheReason)
{
    const std::pair<const char*, const char*> cases[] = {
        {"sim integrators --out", "--out: expected a value (FILE.csv), got none"},
        {"field --at", "--at: expected a value (X,Y,Z), got none"},
        {"field --at 1,2", "--at: expected 3 numbers (x,y,z), got 2"},
        {"field --at 1,2,3,4", "--at: expected 3 numbers (x,y,z), got 4"},
        {"render integrators", "--out: required; give it a value (PATH)"},
        {"bench --windows 0", "--windows: must be from 1 to 100, got 0"},
        {"field --slice --resolution 5", "--resolution: must be from 16 to 2000, got 5"},
        {"bench --peer-worker --phase x", "--phase: unknown value 'x' (expected one of: flight, landed, rested)"},
        {"bench --phases --peer-worker", "--peer-worker: not with --phases"},
        {"bench --iterations 5", "--iterations: only with --pile-worker"}};
    for (const auto& [args, message] : cases) {
        const CommandResult r = runPba(args);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(r.err, std::string("pba: error: ") + message + "\n");
        EXPECT_EQ(r.out, "") << args;
    }
}

// The incline's lesson in pba sim's words: the steep ramp's box slides at g (sin 35 - 0.5 cos 35).
TEST(PbaSim, SaysHowFastTheInclinesBoxSlides)
{
    const CommandResult r = runPba("sim incline");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("slides on steep-ramp without turning from t = 0.005 to"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("its speed changing at 1.609 m/s^2"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("gentle-box: still from t = 0.010 s, its -y face down (tilted 20.00 degrees); slides"),
              std::string::npos) << r.out;
}

// A body flung a thousand kilometres up keeps its row's columns: its highest point and final
// position in figures (1.272e+06), where four decimals overflowed the columns and pushed the rest
// of the row along.
TEST(PbaSim, AHighestPointFarUpKeepsTheColumns)
{
    const auto dir = freshDir("sim_far_up");
    std::ofstream(dir / "up.json") << R"({"dt": 1, "duration": 600, "gravity": [0, -9.81, 0], )"
                                    << R"("particles": [{"name": "b", "position": [0, 0, 0], "velocity": [0, 5000, 0]}]})";
    const CommandResult r = runPba("sim " + (dir / "up.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::istringstream lines(r.out);
    std::string header, row;
    while (std::getline(lines, header) && header.rfind("body ", 0) != 0) {
    }
    ASSERT_TRUE(std::getline(lines, row)) << r.out;
    // The row's last three columns (highest y, bounces, energy ratio) end where the header's do.
    EXPECT_EQ(row.size(), header.size()) << header << "\n" << row;
    EXPECT_NE(row.find(" 1.272e+06 "), std::string::npos) << row;
    EXPECT_NE(row.find("(0.0000, 1.231e+06, 0.0000)"), std::string::npos) << row;
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

// A built-in's name is the built-in even when a file here has that name; the note says how to
// reach the file.
TEST(PbaSim, AFileNamedLikeABuiltinSceneIsNamedInANote)
{
    const auto dir = freshDir("sim_shadowed");
    std::ofstream(dir / "pendulum") << "not a scene";
    const CommandResult r = runPbaArgv({"sim", "pendulum", "--duration", "0.01"}, {.workDir = dir});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "pba: note: 'pendulum' is the built-in scene; for the file of that name here, give ./pendulum\n");
    const CommandResult file = runPbaArgv({"sim", "./pendulum"}, {.workDir = dir});
    EXPECT_EQ(file.exitCode, 2) << file.err;
    EXPECT_EQ(file.err.find("note"), std::string::npos) << file.err;
}

// What the summary says of what is not there: an empty swarm has no heights, a body never in
// the dryer's cone no height in it; a box slides on the ground where there is no room; XPBD's
// springs meet the room in their substeps, so no response is turned into another for them.
TEST(PbaSim, TheSummaryNamesWhatIsNotThereInWords)
{
    const auto dir = freshDir("sim_summary_words");
    std::ofstream(dir / "empty.json")
        << R"({"swarms": [{"name": "s", "count": 0, "region": {"min": [0, 1, 0], "max": [1, 2, 1]}, "seed": 1}],
              "forces": [{"type": "blow-dryer", "nozzle": [0, 0, 0], "axis": [0, 1, 0], "height": 2, "top_radius": 1, "strength": 1}],
              "rigid_bodies": [{"name": "box", "position": [1.5, 0.1, 0], "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}}]})";
    const CommandResult empty = runPbaArgv({"sim", (dir / "empty.json").string(), "--duration", "0.1"});
    ASSERT_EQ(empty.exitCode, 0) << empty.err;
    EXPECT_NE(empty.out.find("swarm s: no particles"), std::string::npos) << empty.out;
    EXPECT_EQ(empty.out.find("inf"), std::string::npos) << empty.out;
    EXPECT_EQ(std::regex_search(empty.out, std::regex("nan", std::regex::icase)), false) << empty.out;

    std::ofstream(dir / "slide.json")
        << R"({"dt": 0.005, "duration": 1, "ground": {"height": 0}, "rigid_bodies": [{"name": "b",
              "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "position": [0, 0.1, 0], "velocity": [2, 0, 0]}]})";
    const CommandResult slide = runPbaArgv({"sim", (dir / "slide.json").string()});
    EXPECT_NE(slide.out.find("slides on the ground"), std::string::npos) << slide.out;

    const CommandResult xpbd = runPba("sim rope --integrator xpbd --duration 0.01");
    EXPECT_EQ(xpbd.out.find("reflect for bodies joined by springs"), std::string::npos) << xpbd.out;
    const CommandResult implicit = runPba("sim rope --duration 0.01");
    EXPECT_NE(implicit.out.find("reflect for bodies joined by springs"), std::string::npos) << implicit.out;
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

namespace {

/// An ordinary edit of a built-in scene that makes it blow up, and what the message must name.
struct BlowUp {
    const char* label;
    const char* scene;
    std::function<void(nlohmann::json&)> edit;
    std::vector<std::string> args; ///< more arguments for `pba sim`
    const char* body;              ///< the body the message names ("" to take any)
    const char* reason;            ///< a part of the message
};

void PrintTo(const BlowUp& b, std::ostream* os) { *os << b.label; }

std::vector<BlowUp> blowUps()
{
    return {
        {"picogram box in the dryer", "blow-dryer-boxes", [](nlohmann::json& s) { s["rigid_bodies"][0]["mass"] = 1e-12; },
         {}, "light", " of work its energy sources did"},
        {"picogram box in drag", "dice",
         [](nlohmann::json& s) {
             s["rigid_bodies"] = nlohmann::json::array({s["rigid_bodies"][0]});
             s["rigid_bodies"][0].erase("density");
             s["rigid_bodies"][0]["mass"] = 1e-12;
             s["forces"] = nlohmann::json::parse(R"([{"type": "drag", "coefficient": 0.05}])");
         },
         {}, "die0", " the energy "},
        {"gravity 1e200 on the dryer's boxes", "blow-dryer-boxes", [](nlohmann::json& s) { s["gravity"] = {0, -1e200, 0}; },
         {}, "light", "the orientation of body 'light' is not finite"},
        {"rope of stiffness 1e300", "rope", [](nlohmann::json& s) { s["ropes"][0]["stiffness"] = 1e300; }, {}, "",
         "no energy source"},
        {"rope with dampers of 1e300", "rope", [](nlohmann::json& s) { s["ropes"][0]["damping"] = 1e300; }, {}, "",
         "no energy source"},
        {"rope at dt 0.05", "rope", [](nlohmann::json&) {}, {"--dt", "0.05"}, "", "no energy source"},
        // (A ball thrown down at 1e50 m/s used to end its step half in the floor; the contact
        // pipeline now stops it on the floor: RigidBlowUp.ABallThrownAtTenToTheFifty... .)
    };
}

} // namespace

class PbaSimBlowUp : public testing::TestWithParam<BlowUp> {};

// Each of these ended in exit 1 ("an orientation must be a non-zero finite quaternion") with its
// CSV dropped, or in exit 0 with the energy up by up to 1e300: now exit 3, one line naming the
// body, the step and the time, and the CSV holds every row up to the step before.
TEST_P(PbaSimBlowUp, ExitsThreeNamingTheBodyAndKeepsTheRowsUpToTheLastGoodStep)
{
    const BlowUp& b = GetParam();
    const auto dir = freshDir("sim_blow_up");
    nlohmann::json scene = nlohmann::json::parse(pba::builtinSceneText(b.scene));
    b.edit(scene);
    std::ofstream(dir / "scene.json") << scene.dump();
    std::vector<std::string> args{"sim", (dir / "scene.json").string(), "--out", (dir / "run.csv").string()};
    args.insert(args.end(), b.args.begin(), b.args.end());
    const CommandResult r = runPbaArgv(args);
    ASSERT_EQ(r.exitCode, 3) << r.err << r.out;
    EXPECT_EQ(r.err.rfind("pba: error: " + (dir / "scene.json").string() + ": ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(std::string("body '") + b.body), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(b.reason), std::string::npos) << r.err;
    const std::size_t at = r.err.find(" at step ");
    ASSERT_NE(at, std::string::npos) << r.err;
    const long failed = std::stol(r.err.substr(at + 9));
    EXPECT_NE(r.err.find("(t = "), std::string::npos) << r.err;
    // Every row up to the last good step, each of them finite.
    std::istringstream csv(readFile(dir / "run.csv"));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line.rfind("step,t,body", 0), 0u) << line;
    long lastStep = -1;
    while (std::getline(csv, line)) {
        EXPECT_EQ(line.find("nan"), std::string::npos) << line;
        EXPECT_EQ(line.find("inf"), std::string::npos) << line;
        lastStep = std::stol(line.substr(0, line.find(',')));
    }
    EXPECT_EQ(lastStep, failed - 1);
}

INSTANTIATE_TEST_SUITE_P(Issue60, PbaSimBlowUp, testing::ValuesIn(blowUps()),
                         [](const testing::TestParamInfo<BlowUp>& each) {
                             std::string name = each.param.label;
                             for (char& c : name)
                                 c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                             return name;
                         });

// Forward Euler gains energy on the integrators scene (half as much again by its end): that is
// the lesson of the practical, not a blow-up.
TEST(PbaSim, ForwardEulersOrdinaryGainIsNoBlowUp)
{
    const CommandResult r = runPba("sim integrators --integrator forward-euler");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
}

TEST(PbaSim, HelpSaysWhatExitThreeMeans)
{
    for (const char* args : {"--help", "sim --help"}) {
        const CommandResult r = runPba(args);
        ASSERT_EQ(r.exitCode, 0);
        for (const char* part : {"3 simulation failure", "a state not finite", "inside a wall", "100 times its scale"}) {
            if (std::string(args) == "sim --help" && std::string(part) == "3 simulation failure")
                continue; // sim's help says "Exit status 3"
            EXPECT_NE(r.out.find(part), std::string::npos) << args << ": " << part << "\n" << r.out;
        }
    }
}

// A rope or cloth is one row of totals, not a row per particle (on request, those too); the
// whole scene's energy and momentum close the table: two free particles in no gravity have
// exactly their start's, m1 v1 + m2 v2 = 1 * 2 + 0.5 * (-2) = 1 kg m/s along x, and
// 1/2 (1 * 4 + 0.5 * 4) = 3 J.
TEST(PbaSim, ARopeOrClothIsOneRowAndTheSceneHasTotals)
{
    const CommandResult cloth = runPba("sim cloth --duration 0.05");
    ASSERT_EQ(cloth.exitCode, 0) << cloth.err;
    EXPECT_NE(cloth.out.find("cloth sheet                  144 semi-implicit-euler"), std::string::npos) << cloth.out;
    EXPECT_EQ(cloth.out.find("sheet[3,3]"), std::string::npos) << "no row per particle";
    EXPECT_LT(std::count(cloth.out.begin(), cloth.out.end(), '\n'), 8) << cloth.out;
    EXPECT_NE(cloth.out.find("all bodies: energy"), std::string::npos) << cloth.out;
    const CommandResult every = runPba("sim cloth --duration 0.05 --every-particle");
    EXPECT_NE(every.out.find("sheet[3,3]"), std::string::npos);

    const auto dir = freshDir("sim_totals");
    std::ofstream(dir / "pair.json") << R"({"gravity": [0, 0, 0], "particles": [
        {"name": "a", "position": [0, 1, 0], "velocity": [2, 0, 0], "mass": 1, "integrator": "velocity-verlet"},
        {"name": "b", "position": [0, 2, 0], "velocity": [-2, 0, 0], "mass": 0.5, "integrator": "velocity-verlet"}]})";
    const CommandResult pair = runPba("sim " + (dir / "pair.json").string() + " --duration 1");
    ASSERT_EQ(pair.exitCode, 0) << pair.err;
    EXPECT_NE(pair.out.find("all bodies: energy 3 J, 3 J at the start: E now/E start 1.000000; momentum (1.0000, "
                            "0.0000, 0.0000) kg m/s, (1.0000, 0.0000, 0.0000) at the start"),
              std::string::npos)
        << pair.out;
}

namespace {

/// The number after `label` in sim's output (NaN if the label is not there).
double numberAfter(const std::string& out, const std::string& label)
{
    const std::size_t at = out.find(label);
    return at == std::string::npos ? NAN : std::stod(out.substr(at + label.size()));
}

} // namespace

// What the scenes' descriptions claim of contacts, joints and the energy, sim measures: the dice
// overlap by under 5 mm and are all asleep by 3 s; the chain's hinges hold within a millimetre and
// its energy never grows from one step to the next.
TEST(PbaSim, ContactsJointsAndTheEnergysStepsAreMeasured)
{
    const CommandResult dice = runPba("sim dice");
    ASSERT_EQ(dice.exitCode, 0) << dice.err;
    EXPECT_LT(numberAfter(dice.out, "contacts: the deepest overlap of two bodies "), 5.0) << dice.out; // mm
    EXPECT_LT(numberAfter(dice.out, "every moving body asleep from t = "), 3.0) << dice.out;
    const CommandResult chain = runPba("sim chain");
    ASSERT_EQ(chain.exitCode, 0) << chain.err;
    EXPECT_LT(numberAfter(chain.out, "joints: held to "), 1e-3) << chain.out;
    EXPECT_NE(chain.out.find("the energy never rose from one step to the next"), std::string::npos) << chain.out;
    const CommandResult drop = runPba("sim integrators --duration 2");
    EXPECT_GT(numberAfter(drop.out, "the energy rose by at most "), 0.0) << "forward Euler's gain: " << drop.out;
    EXPECT_EQ(drop.out.find("joints:"), std::string::npos) << "no joints, no line";
}

// What the descriptions claim of tilts, swings, balls and heaps, sim measures: the pendulum at
// its highest every half period, the light box in the jet tilting by up to 26.5 degrees, the
// sheet (its balls and the edges between them) never more than a millimetre into the box and at
// rest, the balls in the dryer one clump from 2.6 s, the grains' mound steep and their overlaps small.
TEST(PbaSim, TiltsSwingsBallsAndHeapsAreMeasured)
{
    const CommandResult pendulum = runPba("sim pendulum --duration 5");
    ASSERT_EQ(pendulum.exitCode, 0) << pendulum.err;
    EXPECT_NEAR(numberAfter(pendulum.out, "at its highest every "), 2.1572 / 2.0, 1e-3) << pendulum.out;
    const CommandResult boxes = runPba("sim blow-dryer-boxes");
    EXPECT_NEAR(numberAfter(boxes.out, "light: moving at the end; its start's up tilted by up to "), 26.5, 0.5) << boxes.out;
    const CommandResult sheet = runPba("sim cloth-on-box");
    EXPECT_LT(numberAfter(sheet.out, "one went "), 1.0) << sheet.out; // mm
    EXPECT_LT(numberAfter(sheet.out, "edge or cell between its balls went "), 1.0) << sheet.out; // mm
    EXPECT_LT(numberAfter(sheet.out, "the fastest at "), 0.01) << sheet.out;
    const CommandResult balls = runPba("sim balls-in-the-dryer --duration 10");
    EXPECT_NEAR(numberAfter(balls.out, "touch as one group (within 1 mm, or 1% of their radii if less) from t = "), 2.62, 0.1) << balls.out;
    const CommandResult grains = runPba("sim granular");
    EXPECT_GT(numberAfter(grains.out, "mound stands at "), 25.0) << grains.out;
    EXPECT_LT(numberAfter(grains.out, "the deepest two grains overlap by "), 0.1) << grains.out;
}

// A free ball dropped on a tightrope between two of its balls: sim says how far it went into the
// rope's edge between them (the rope holds it: under a millimetre).
TEST(PbaSim, AFreeBallInARopesEdgeIsMeasured)
{
    const auto dir = freshDir("sim_ball_on_edge");
    std::ofstream(dir / "tightrope.json") << R"({"dt": 0.002, "gravity": [0, -9.81, 0],
        "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "ropes": [{"name": "rope", "from": [-0.6, 1, 0], "to": [0.6, 1, 0], "count": 5, "mass": 0.5,
                   "pinned": ["start", "end"], "stiffness": 2000, "damping": 20, "radius": 0.02, "restitution": 0}],
        "particles": [{"name": "ball", "position": [0.15, 1.5, 0], "mass": 0.1, "radius": 0.05, "restitution": 0}]})";
    const CommandResult r = runPba("sim " + (dir / "tightrope.json").string() + " --duration 3");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_LT(numberAfter(r.out, "a free ball went "), 1.0) << r.out; // mm
}

// A short rope of thick balls laid along a tightrope, its balls between the tightrope's: each net's
// balls meet the other's edges, and the summary says how far one went in.
TEST(PbaSim, ARopesBallInAnotherRopesEdgeIsMeasured)
{
    const auto dir = freshDir("sim_rope_on_rope");
    std::ofstream(dir / "ropes.json") << R"({"dt": 0.002, "gravity": [0, -9.81, 0],
        "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "ropes": [{"name": "tightrope", "from": [-0.6, 1, 0], "to": [0.6, 1, 0], "count": 5, "mass": 0.5,
                   "pinned": ["start", "end"], "stiffness": 2000, "damping": 20, "radius": 0.02, "restitution": 0},
                  {"name": "short", "from": [-0.45, 1.3, 0], "to": [0.45, 1.3, 0], "count": 4, "mass": 0.2,
                   "stiffness": 2000, "damping": 5, "radius": 0.04, "restitution": 0}]})";
    const CommandResult r = runPba("sim " + (dir / "ropes.json").string() + " --duration 3");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_LT(numberAfter(r.out, "a rope's or cloth's ball or edge went "), 1.0) << r.out; // mm
    EXPECT_GT(numberAfter(r.out, "rope short at the end: its particles "), 0.9) << r.out; // m: on the tightrope
}

// A component that rounds to zero prints as 0.0000, not -0.0000: a box resting on the floor read
// (0.0000, 0.2000, -0.0000).
TEST(PbaSim, NothingPrintsAsMinusZero)
{
    const auto dir = freshDir("sim_minus_zero");
    std::ofstream(dir / "boxes.json") << R"({"ground": {"height": 0}, "rigid_bodies": [
        {"name": "rest", "shape": {"type": "box", "size": [0.4, 0.4, 0.4]}, "position": [0, 0.2, 0]},
        {"name": "fall", "shape": {"type": "box", "size": [0.4, 0.4, 0.4]}, "position": [3, 2, 0]}]})";
    const CommandResult r = runPba("sim " + (dir / "boxes.json").string() + " --duration 3");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.find("-0.0000"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("(-0.000,"), std::string::npos) << r.out;
}

// A body with no energy at the start has no ratio: a dash, where one set moving by a joint read 1.
TEST(PbaSim, NoEnergyAtTheStartIsNoRatio)
{
    const auto dir = freshDir("sim_no_ratio");
    std::ofstream(dir / "pair.json") << R"({"gravity": [0, 0, 0], "particles": [
        {"name": "still", "position": [0, 1, 0], "mass": 1},
        {"name": "moving", "position": [0, 2, 0], "velocity": [1, 0, 0], "mass": 1}]})";
    const CommandResult r = runPba("sim " + (dir / "pair.json").string() + " --duration 0.1");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::size_t still = r.out.find("\nstill ");
    ASSERT_NE(still, std::string::npos) << r.out;
    const std::string row = r.out.substr(still + 1, r.out.find('\n', still + 1) - still - 1);
    EXPECT_EQ(row.back(), '-') << row;
    EXPECT_NE(r.out.find("E now/E start 1.000000"), std::string::npos) << r.out; // the totals: 0.5 J of 0.5 J
}

// The fixed ramps' height energy never changes and is left out of the totals: the incline's boxes,
// the one sliding down to the floor, end with 0.46 of the energy they started with (0.997 with the
// ramps counted); moving and fixed alike, the totals are the rows' sums.
TEST(PbaSim, TheTotalsAreTheMovingBodiesWhereSomeAreFixed)
{
    const CommandResult incline = runPba("sim incline");
    ASSERT_EQ(incline.exitCode, 0) << incline.err;
    const std::size_t at = incline.out.find("all moving bodies: energy ");
    ASSERT_NE(at, std::string::npos) << incline.out;
    const std::size_t ratioAt = incline.out.find("E now/E start ", at);
    ASSERT_NE(ratioAt, std::string::npos);
    const double ratio = std::stod(incline.out.substr(ratioAt + 14, 8));
    EXPECT_GT(ratio, 0.3);
    EXPECT_LT(ratio, 0.6);
    EXPECT_EQ(runPba("sim bouncing-cube --duration 1").out.find("all moving bodies"), std::string::npos)
        << "nothing fixed: all bodies";
}

// The blow dryer does work on a ball in its cone: its energy ratio (1.76 after 5 s) says so
// beside it, and a line gives that work and the ratio without it; a scene without a dryer says
// nothing of it.
TEST(PbaSim, TheDryersWorkIsNamedBesideTheEnergyRatio)
{
    const CommandResult dryer = runPba("sim blow-dryer --duration 5");
    ASSERT_EQ(dryer.exitCode, 0) << dryer.err;
    const auto row = dryer.out.find("\nball ");
    ASSERT_NE(row, std::string::npos) << dryer.out;
    const std::string line = dryer.out.substr(row + 1, dryer.out.find('\n', row + 1) - row - 1);
    EXPECT_NE(line.find("1.76"), std::string::npos) << line;
    EXPECT_NE(line.find("(+ the dryer's work)"), std::string::npos) << line;
    EXPECT_NE(dryer.out.find("the blow dryer did 12.4"), std::string::npos) << dryer.out;
    EXPECT_NE(dryer.out.find("the balance: 16.19 J at the start + 12.4381 J of work - 28.53 J now = 0.0981 J taken "
                             "by bounces, contacts and the integration, 0.606% of the start's energy"),
              std::string::npos)
        << dryer.out;
    const CommandResult plain = runPba("sim integrators --duration 1");
    EXPECT_EQ(plain.out.find("dryer"), std::string::npos) << plain.out;
}

// The dryer's work is summed as semi-implicit Euler gives it (its force at each step's start
// against the step's mean velocity), so on blow-dryer-flow, whose five balls start and end at
// rest and touch nothing, the balance closes to rounding.
TEST(PbaSim, TheDryersWorkClosesTheEnergyBalanceOfBallsThatTouchNothing)
{
    const CommandResult flow = runPba("sim blow-dryer-flow");
    ASSERT_EQ(flow.exitCode, 0) << flow.err;
    const std::string by = " by bounces, contacts and the integration, ";
    const auto at = flow.out.find(by);
    ASSERT_NE(at, std::string::npos) << flow.out;
    const double percent = std::stod(flow.out.substr(at + by.size())); // "2.77e-12% of the start's energy"
    EXPECT_LT(percent, 1e-7) << flow.out.substr(at);
}

// Balls that collide for a minute lose more than their start's energy, paid for by the dryer's
// work: the balance says so in joules, where a ratio (E now - W) / E start read -0.13.
TEST(PbaSim, TheDryersBalanceIsInJoulesWhenTheLossOutgrowsTheStart)
{
    const CommandResult balls = runPba("sim balls-in-the-dryer");
    ASSERT_EQ(balls.exitCode, 0) << balls.err;
    EXPECT_NE(balls.out.find("the balance: 85.0935 J at the start + 157.187 J of work - 144.533 J now = 97.7 J taken by "
                             "bounces, contacts and the integration, 115% of the start's energy"),
              std::string::npos)
        << balls.out;
}

// A particle whose exact motion is known is set beside it at the end: spring's bob against
// y = 3 - cos(sqrt(10) t) at t = 10 s, 2.0213 m; integrators' two dropped balls against their
// elastic bounces, forward Euler's far off (it gained height), semi-implicit Euler's near.
TEST(PbaSim, AParticleIsSetBesideItsExactSolution)
{
    const CommandResult spring = runPba("sim spring");
    ASSERT_EQ(spring.exitCode, 0) << spring.err;
    const double y = 3.0 - std::cos(std::sqrt(10.0) * 10.0);
    EXPECT_NE(spring.out.find(fmt::format("puts it at (0.0000, {:.4f}, 0.0000) at t = 10 s", y)), std::string::npos)
        << spring.out;
    const CommandResult drop = runPba("sim integrators");
    EXPECT_GT(numberAfter(drop.out, "forward-euler: the exact solution (elastic bounces from 2 m, every 1.277 s) puts it at "
                                    "(0.0000, 1.7694, 0.0000) at t = 10 s: "), 1.0) << drop.out;
    EXPECT_LT(numberAfter(drop.out, "semi-implicit-euler: the exact solution (elastic bounces from 2 m, every 1.277 s) "
                                    "puts it at (0.5000, 1.7694, 0.0000) at t = 10 s: "), 0.1) << drop.out;
    EXPECT_EQ(runPba("sim blow-dryer --duration 1").out.find("exact solution"), std::string::npos);
}

// The balance names the scene's drag and damped springs among what took the energy, and a dryer
// that took energy (a ping-pong ball slowed by the air) as work subtracted, not "+ -0.008 J".
TEST(PbaSim, TheDryersBalanceNamesDragDampingAndWorkTaken)
{
    const CommandResult boxes = runPba("sim blow-dryer-boxes --duration 2");
    EXPECT_NE(boxes.out.find(" taken by bounces, contacts, drag and the integration, "), std::string::npos) << boxes.out;
    const CommandResult sheet = runPba("sim cloth-in-the-dryer --duration 2");
    EXPECT_NE(sheet.out.find(" by bounces, contacts, the springs' damping and the integration, "), std::string::npos)
        << sheet.out;
    const CommandResult ball = runPba("sim ping-pong");
    EXPECT_NE(ball.out.find(" J at the start - "), std::string::npos) << ball.out;
    EXPECT_EQ(ball.out.find("+ -"), std::string::npos) << ball.out;
    EXPECT_EQ(ball.out.find("\nballs ("), std::string::npos) << "a lone ball has no overlaps to tell: " << ball.out;
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
