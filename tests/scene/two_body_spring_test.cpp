// The two-body spring in a scene file: it loads beside the anchored form, joins particles that
// must share one integrator (exit 2 naming the spring otherwise), and runs through `pba sim`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "pba/forces.hpp"
#include "pba/scene/scene.hpp"
#include "support/run_command.hpp"

using namespace pba;
using namespace pba::test;

namespace {

std::string pairScene(const std::string& secondIntegrator, const std::string& springExtra = "")
{
    return R"({
  "name": "pair", "dt": 0.005, "duration": 1, "ground": { "height": 0 },
  "particles": [
    { "name": "a", "position": [-0.6, 1, 0], "integrator": "rk4" },
    { "name": "b", "position": [0.6, 1.5, 0], "integrator": ")" +
           secondIntegrator + R"(" },
    { "name": "c", "position": [2, 2, 0], "integrator": "forward-euler" }
  ],
  "forces": [
    { "type": "spring", "particle": "c", "anchor": [2, 3, 0], "stiffness": 5 },
    { "type": "spring", "particles": ["a", "b"], "stiffness": 40, "rest_length": 1, "damping": 0.2)" +
           springExtra + R"( }
  ]
})";
}

} // namespace

TEST(TwoBodySpring, LoadsBesideTheAnchoredForm)
{
    const Scene scene = parseScene(pairScene("rk4"), "pair.json");
    ASSERT_EQ(scene.world.forceCount(), 3u); // gravity, the anchored spring, the two-body spring
    const auto* spring = dynamic_cast<const TwoBodySpring*>(&scene.world.force(2));
    ASSERT_NE(spring, nullptr);
    EXPECT_EQ(spring->first(), 0u);
    EXPECT_EQ(spring->second(), 1u);
    EXPECT_EQ(spring->stiffness(), 40.0);
    EXPECT_EQ(spring->restLength(), 1.0);
    EXPECT_EQ(spring->damping(), 0.2);
    EXPECT_NE(dynamic_cast<const Spring*>(&scene.world.force(1)), nullptr);
    EXPECT_TRUE(scene.world.isCoupled(0));
    EXPECT_FALSE(scene.world.isCoupled(2));
}

TEST(TwoBodySpring, MixedIntegratorsAreRefusedNamingTheSpring)
{
    try {
        (void)parseScene(pairScene("semi-implicit-euler"), "pair.json");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.field(), "forces[1].particles");
        EXPECT_NE(e.reason().find("'a' (rk4)"), std::string::npos) << e.reason();
        EXPECT_NE(e.reason().find("'b' (semi-implicit-euler)"), std::string::npos) << e.reason();
    }
}

TEST(TwoBodySpring, BadFormsAreSceneErrors)
{
    auto fieldOf = [](const std::string& text) {
        try {
            (void)parseScene(text, "pair.json");
        } catch (const SceneError& e) {
            return e.field();
        }
        return std::string("(no error)");
    };
    EXPECT_EQ(fieldOf(pairScene("rk4", R"(, "anchor": [0, 0, 0])")), "forces[1].anchor");
    EXPECT_EQ(fieldOf(pairScene("rk4", R"(, "particle": "a")")), "forces[1].particle");
    std::string self = pairScene("rk4");
    self.replace(self.find(R"(["a", "b"])"), 10, R"(["a", "a"])");
    EXPECT_EQ(fieldOf(self), "forces[1].particles");
    std::string one = pairScene("rk4");
    one.replace(one.find(R"(["a", "b"])"), 10, R"(["a"])");
    EXPECT_EQ(fieldOf(one), "forces[1].particles");
    std::string unknown = pairScene("rk4");
    unknown.replace(unknown.find(R"(["a", "b"])"), 10, R"(["a", "z"])");
    EXPECT_EQ(fieldOf(unknown), "forces[1].particles");
}

TEST(TwoBodySpring, RunsThroughPbaSimAndMixedIsExitTwo)
{
    const auto dir = std::filesystem::temp_directory_path() / ("pba_two_body_spring_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "pair.json") << pairScene("rk4");
    std::ofstream(dir / "mixed.json") << pairScene("velocity-verlet");
    const CommandResult ok = runPba("sim " + (dir / "pair.json").string() + " --duration 2");
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
    EXPECT_NE(ok.out.find("pair"), std::string::npos) << ok.out;
    // The header says what the collision response does to the pair (see docs/scenes.md).
    const CommandResult exact = runPba("sim " + (dir / "pair.json").string() + " --duration 0.1 --collision exact");
    EXPECT_NE(exact.out.find("collision response exact (reflect for bodies joined by springs)"), std::string::npos)
        << exact.out;
    // --integrator sets every moving particle's after loading: the group stays consistent.
    const CommandResult overridden = runPba("sim " + (dir / "pair.json").string() + " --integrator forward-euler");
    EXPECT_EQ(overridden.exitCode, 0) << overridden.err;
    // The file itself must follow the rule, whatever the command line overrides.
    const CommandResult mixed = runPba("sim " + (dir / "mixed.json").string() + " --integrator rk4");
    EXPECT_EQ(mixed.exitCode, 2);
    EXPECT_NE(mixed.err.find("forces[1].particles"), std::string::npos) << mixed.err;
    std::filesystem::remove_all(dir);
}
