// Hardening II: swarms are checked like bodies, and numbers that cannot be computed with are
// refused at load, naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "pba/forces.hpp"
#include "pba/scene/scene.hpp"
#include "pba/world.hpp"
#include "support/run_command.hpp"

using namespace pba;
using namespace pba::test;

namespace {

struct BadNumber {
    const char* json;
    const char* field;
};

constexpr const char* kSwarm =
    R"("swarms": [{"name": "rain", "count": 10, "region": {"min": [0, 1, 0], "max": [0, 1, 0]}, "seed": 1)";

/// A swarm that forward Euler blows up: drag c with c dt / m = 1e30 multiplies the velocity by
/// -1e30 a step, past float's largest number in the second step.
World explodingSwarm()
{
    Scene scene = parseScene(std::string("{\"ground\": {\"height\": 0}, ") + kSwarm +
                                 R"(, "integrator": "forward-euler", "velocity": [0, 1, 0]}],
                                    "forces": [{"type": "drag", "coefficient": 1e32}]})",
                             "exploding");
    return scene.world;
}

} // namespace

class UnrepresentableNumbers : public ::testing::TestWithParam<BadNumber> {};

TEST_P(UnrepresentableNumbers, AreRefusedAtLoadNamingTheField)
{
    try {
        parseScene(GetParam().json, "bad.json");
        FAIL() << "loaded: " << GetParam().json;
    } catch (const SceneError& error) {
        EXPECT_EQ(error.field(), GetParam().field) << error.what();
    }
}

INSTANTIATE_TEST_SUITE_P(
    Hardening, UnrepresentableNumbers,
    ::testing::Values(
        BadNumber{R"({"ground": {"height": 0}, "swarms": [{"name": "s", "count": 1, "region": {"min": [0, 1, 0],
                      "max": [0, 1, 0]}, "seed": 1, "mass": 1e-300}]})",
                  "swarms[0].mass"},
        BadNumber{R"({"ground": {"height": 0}, "swarms": [{"name": "s", "count": 1, "region": {"min": [0, 1, 0],
                      "max": [0, 1, 0]}, "seed": 1, "velocity": [1e39, 0, 0]}]})",
                  "swarms[0].velocity"},
        BadNumber{R"({"ground": {"height": 0}, "gravity": [0, -1e39, 0], "swarms": [{"name": "s", "count": 1,
                      "region": {"min": [0, 1, 0], "max": [0, 1, 0]}, "seed": 1}]})",
                  "gravity"},
        BadNumber{R"({"ground": {"height": 0}, "swarms": [{"name": "s", "count": 1, "region": {"min": [0, 1, 0],
                      "max": [0, 1, 0]}, "seed": 1}], "forces": [{"type": "blow-dryer", "nozzle": [0, 0, 0],
                      "height": 1, "top_radius": 1, "strength": 1e39}]})",
                  "forces[0]"},
        BadNumber{R"({"forces": [{"type": "blow-dryer", "nozzle": [0, 0, 0], "height": 1, "top_radius": 1,
                      "strength": 1e308}]})",
                  "forces[0].strength"},
        BadNumber{R"({"forces": [{"type": "blow-dryer", "nozzle": [0, 0, 0], "height": 1e200, "top_radius": 1e200,
                      "strength": 1}]})",
                  "forces[0].strength"}));

TEST(SwarmChecks, ANonFiniteParticleStopsTheStepNamingSwarmParticleStepAndQuantity)
{
    World world = explodingSwarm();
    world.step(0.01);
    try {
        world.step(0.01);
        FAIL() << "the second step overflows float";
    } catch (const NonFiniteStateError& error) {
        EXPECT_EQ(error.body(), "rain[0]");
        EXPECT_EQ(error.step(), 2u);
        EXPECT_EQ(error.quantity(), "position"); // thrown 1e28 m below the ground: no finite mirror
    }
}

// With rollback (the viewer's setting) the swarm is back where it was before the failed step,
// with the bodies; without it a program stops there and the swarm keeps the failed state.
TEST(SwarmChecks, BodiesAndSwarmsRollBackTogether)
{
    World world = explodingSwarm();
    world.setSwarmRollback(true);
    Particle p;
    p.setPos(dvec3(0, 2, 0));
    world.addParticle(p);
    world.step(0.01);
    const Vec3<float> before = world.swarm(0).velocity(3);
    const dvec3 body = world.body(0).getPos();
    EXPECT_THROW(world.step(0.01), NonFiniteStateError);
    EXPECT_EQ(world.swarm(0).velocity(3), before);
    EXPECT_EQ(world.body(0).getPos(), body);
    EXPECT_FALSE(world.swarm(0).nonFinite().has_value());
}

TEST(SwarmChecks, PbaSimExitsThreeNamingTheParticle)
{
    const auto dir = freshDir("swarm_nan");
    std::ofstream(dir / "s.json") << std::string("{\"ground\": {\"height\": 0}, \"duration\": 1, ") + kSwarm +
                                         R"(, "integrator": "forward-euler", "velocity": [0, 1, 0]}],
                                            "forces": [{"type": "drag", "coefficient": 1e32}]})";
    const CommandResult r = runPbaArgv({"sim", (dir / "s.json").string()});
    EXPECT_EQ(r.exitCode, 3);
    EXPECT_NE(r.err.find("the position of body 'rain[0]' is not finite at step 2"), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
}

struct BadFlags {
    std::vector<std::string> args;
    const char* says;
};

void PrintTo(const BadFlags& bad, std::ostream* os)
{
    for (const auto& a : bad.args)
        *os << a << ' ';
}

class NumericFlags : public ::testing::TestWithParam<BadFlags> {};

// Each of these crashed, hung or printed nonsense: now exit 2, one line naming the flag, and no
// output file.
TEST_P(NumericFlags, ThatCannotBeRunAreBadInputInOneLine)
{
    const auto dir = freshDir("numeric_flags");
    std::vector<std::string> args = GetParam().args;
    for (auto& a : args)
        if (a == "OUT.mp4" || a == "OUT.png" || a == "OUT")
            a = (dir / a).string();
    const CommandResult r = runPbaArgv(args);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(GetParam().says), std::string::npos) << r.err;
    EXPECT_TRUE(std::filesystem::is_empty(dir));
}

INSTANTIATE_TEST_SUITE_P(
    Hardening, NumericFlags,
    ::testing::Values(BadFlags{{"render", "integrators", "--duration", "1e300", "--out", "OUT.mp4"}, "1e+302 steps"},
                      BadFlags{{"render", "integrators", "--time", "1e300", "--out", "OUT.png"}, "--time"},
                      // As the viewer: a picture after the run's end was drawn without a word.
                      BadFlags{{"render", "integrators", "--duration", "1", "--time", "2", "--out", "OUT.png"},
                               "--time: 2 s is past --duration 1 s"},
                      BadFlags{{"bench", "--sizes", "-1"}, "--sizes"}, BadFlags{{"bench", "--sizes", "nan"}, "--sizes"},
                      BadFlags{{"bench", "--sizes", "0"}, "--sizes"}, BadFlags{{"bench", "--sizes", "0.5"}, "--sizes"},
                      BadFlags{{"bench", "--sizes", "1e20"}, "--sizes"},
                      BadFlags{{"compare", "--jobs", "100000", "--out", "OUT"}, "--jobs"},
                      BadFlags{{"compare", "blow-dryer-swarm", "--out", "OUT"}, "no moving particle"},
                      BadFlags{{"sim", "--dt", "1e-12"}, "--dt: 60 s at dt = 1e-12 s is 6e+13 steps"},
                      BadFlags{{"sim", "--frame-rate", "1e300"}, "--frame-rate"},
                      BadFlags{{"sim", "integrators", "--duration", "1e300"}, "--duration"},
                      BadFlags{{"sim", "integrators", "--out", ""}, "--out: empty; give it a value"},
                      // A flag takes no value: the empty word after it is the positional.
                      BadFlags{{"field", "--json", ""}, "SCENE: empty; give it a scene name or a file"},
                      BadFlags{{"help", ""}, "COMMAND: empty; give it a command's name"},
                      // A list flag given twice was merged into one list; sim refuses a repeated flag.
                      BadFlags{{"compare", "--dt", "0.01", "--dt", "0.02", "--out", "OUT"},
                               "--dt: given 2 times; give it once"},
                      BadFlags{{"compare", "--integrators", "rk4", "--integrators", "rk4", "--out", "OUT"},
                               "--integrators: given 2 times; give it once"},
                      BadFlags{{"compare", "--collisions", "exact", "--collisions", "clamp", "--out", "OUT"},
                               "--collisions: given 2 times; give it once"},
                      BadFlags{{"bench", "--sizes", "1e3", "--sizes", "1e5"}, "--sizes: given 2 times; give it once"},
                      BadFlags{{"compare", "--dt", "0.01,abc", "--out", "OUT"}, "--dt: cannot read 'abc' as a number"},
                      // CLI11 dropped a list's empty items, so `rk4,` ran as `rk4`.
                      BadFlags{{"compare", "--integrators", "rk4,", "--out", "OUT"},
                               "--integrators: item 2 of 'rk4,' is empty"},
                      BadFlags{{"compare", "--collisions", ",exact", "--out", "OUT"},
                               "--collisions: item 1 of ',exact' is empty"},
                      BadFlags{{"compare", "--dt", "0.01,,0.02", "--out", "OUT"}, "--dt: item 2 of '0.01,,0.02' is empty"},
                      BadFlags{{"bench", "--sizes", "1e3,"}, "--sizes: item 2 of '1e3,' is empty"},
                      // Read into an unsigned count, -1 was 2^64 - 1 dice.
                      BadFlags{{"bench", "--pile-worker", "--dice", "-1"},
                               "--dice: must be a whole number of at least 1, got -1"},
                      // CLI11 reads numbers with strtold and strtoll(..., 0): 0x10 was 16, inf a dt.
                      BadFlags{{"sim", "integrators", "--dt", "0x10"}, "--dt: cannot read '0x10' as a number"},
                      BadFlags{{"sim", "integrators", "--duration", "inf"}, "--duration: cannot read 'inf'"},
                      BadFlags{{"sim", "integrators", "--substeps", "0x5"}, "--substeps: cannot read '0x5'"},
                      BadFlags{{"sim", "integrators", "--frame-rate", "nan"}, "--frame-rate: cannot read 'nan'"},
                      BadFlags{{"render", "integrators", "--fps", "0x3c", "--out", "OUT.png"}, "--fps: cannot read"},
                      BadFlags{{"render", "integrators", "--time", "0x1p0", "--out", "OUT.png"}, "--time: cannot read"},
                      BadFlags{{"field", "--at", "0,infinity,0"}, "--at: cannot read 'infinity'"},
                      BadFlags{{"field", "--slice", "--resolution", "0x100", "--out", "OUT.png"}, "--resolution"},
                      BadFlags{{"compare", "--dt", "0.01,0x10", "--out", "OUT"}, "--dt: cannot read '0x10'"},
                      BadFlags{{"compare", "--duration", "NaN", "--out", "OUT"}, "--duration: cannot read 'NaN'"},
                      BadFlags{{"compare", "--jobs", "0x2", "--out", "OUT"}, "--jobs: cannot read '0x2'"},
                      BadFlags{{"bench", "--sizes", "0x400"}, "--sizes: cannot read '0x400'"},
                      BadFlags{{"bench", "--windows", "0x2"}, "--windows: cannot read '0x2'"},
                      BadFlags{{"bench", "--pile-worker", "--dice", "0x10"}, "--dice: cannot read '0x10'"},
                      BadFlags{{"bench", "--pile-worker", "--iterations", "0x10"}, "--iterations: cannot read"}));

// A number's leading zeros are a decimal's: --fps 010 is 10 frames a second, not octal's 8.
TEST(NumericFlagsDecimal, LeadingZerosAreRead)
{
    const auto dir = freshDir("leading_zeros");
    const CommandResult r =
        runPbaArgv({"render", "integrators", "--duration", "0.5", "--fps", "010", "--out", (dir / "f").string() + "/"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("(6 frames,"), std::string::npos) << r.out;
    EXPECT_EQ(runPbaArgv({"sim", "integrators", "--dt", "00.5", "--duration", "1"}).out.rfind("scene integrators: 2 "
                                                                                             "steps of dt = 0.5 s",
                                                                                             0),
              0u);
}

// A thin, tall dryer's slice asked for millions of rows of scratch data; it is bounded now.
TEST(NumericFlagsSlice, AThinDryersSliceIsBounded)
{
    const auto dir = freshDir("thin_dryer");
    std::ofstream(dir / "thin.json") << R"({"forces": [{"type": "blow-dryer", "nozzle": [0, 0, 0], "height": 1000,
                                             "top_radius": 0.001, "strength": 10}]})";
    const CommandResult r = runPbaArgv({"field", (dir / "thin.json").string(), "--slice", "--out", (dir / "f.png").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "f.png"));
}
