// Hardening III: inputs refused before they cost anything (memory estimated from the document,
// flags bounded where they are checked), and states that cannot be (a per-particle mass of zero,
// a body that starts in the floor) refused at load, naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "pba/scene/scene.hpp"
#include "support/run_command.hpp"

using namespace pba;
using namespace pba::test;

namespace {

/// The field a scene is refused for ("" if it loads).
std::string refusedField(const std::string& json)
{
    try {
        parseScene(json, "bad.json");
    } catch (const SceneError& error) {
        return error.field();
    }
    return "";
}

/// One line on stderr, exit 2, the field named, and nothing written.
void expectBadInput(const CommandResult& r, const std::filesystem::path& dir, const std::string& says)
{
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1)
        << "only the scene file";
}

} // namespace

// 5e-324 kg over two particles is 0 kg each: Body::setMass refused it with exit 1 and no field.
TEST(StatesThatCannotBe, AFabricMassThatUnderflowsPerParticleIsBadInputNamingTheMass)
{
    const auto dir = freshDir("mass_underflow");
    std::ofstream(dir / "rope.json") << R"({"ground": {"height": 0}, "ropes": [{"name": "r", "from": [0, 1, 0],
                                            "to": [1, 1, 0], "count": 2, "mass": 5e-324, "stiffness": 10}]})";
    const CommandResult r = runPbaArgv({"sim", (dir / "rope.json").string(), "--out", (dir / "out.csv").string()});
    expectBadInput(r, dir, "ropes[0].mass: 5e-324 kg shared among 2 particles is 0 kg each");
    // The smallest normal share still loads: 2 particles of 2.3e-308 kg.
    EXPECT_EQ(refusedField(R"({"ropes": [{"name": "r", "from": [0, 1, 0], "to": [1, 1, 0], "count": 2,
                                "mass": 4.5e-308, "stiffness": 10}]})"), "");
    EXPECT_EQ(refusedField(R"({"cloths": [{"name": "c", "origin": [0, 1, 0], "across": [1, 0, 0], "down": [0, 0, 1],
                                "columns": 2, "rows": 2, "mass": 1e-308, "stiffness": {"structural": 1}}]})"),
              "cloths[0].mass");
}
