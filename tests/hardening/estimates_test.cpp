// Hardening III: inputs refused before they cost anything (memory estimated from the document,
// flags bounded where they are checked), and states that cannot be (a per-particle mass of zero,
// a body that starts in the floor) refused at load, naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

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

/// One line on stderr, exit 2, the field named, and nothing written: `dir` holds its `inputs`
/// files alone.
void expectBadInput(const CommandResult& r, const std::filesystem::path& dir, const std::string& says,
                    long inputs = 1)
{
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), inputs);
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

namespace {

/// `count` copies of `entry` under `kind`, each with its own name, in a scene with a ground.
std::string manyOf(const std::string& kind, nlohmann::json entry, int count)
{
    nlohmann::json scene = {{"ground", {{"height", 0}}}, {kind, nlohmann::json::array()}};
    for (int i = 0; i < count; ++i) {
        entry["name"] = std::to_string(i);
        scene[kind].push_back(entry);
    }
    return scene.dump();
}

const nlohmann::json kBigCloth = {{"origin", {0, 2, 0}}, {"across", {1, 0, 0}}, {"down", {0, 0, 1}},
                                  {"columns", 1000}, {"rows", 1000}, {"stiffness", {{"structural", 100}}}};

/// The scene refused for its memory: the field, and a reason naming the estimate.
void expectRefusedForMemory(const std::string& json, const std::string& fieldStart)
{
    try {
        parseScene(json, "big.json");
        FAIL() << "built it";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.field().rfind(fieldStart, 0), 0u) << e.what();
        EXPECT_NE(e.reason().find("GB of memory available"), std::string::npos) << e.what();
        EXPECT_NE(e.reason().find("needs about"), std::string::npos) << e.what();
    }
}

/// AddressSanitizer reserves terabytes of address space: a pba built with it cannot start under
/// a limit on it, so the tests that set one skip there.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

/// `pba sim SCENE` with at most `kilobytes` of address space.
CommandResult simUnderLimit(const std::filesystem::path& scene, long kilobytes)
{
    return runShell("ulimit -v " + std::to_string(kilobytes) + "; exec '" + std::string(PBA_BINARY) + "' sim '" +
                    scene.string() + "'");
}

} // namespace

// 200 cloths of a million particles (about 200 GB) and 2,000 ropes of 100,000 (about 200 GB) are
// refused before the first is built, naming the one that passes the memory available.
TEST(MemoryEstimates, RopesAndClothsBeyondTheMemoryAreRefusedBeforeBuilding)
{
    expectRefusedForMemory(manyOf("cloths", kBigCloth, 200), "cloths[");
    const nlohmann::json rope = {{"from", {0, 1, 0}}, {"to", {1, 1, 0}}, {"count", 100000}, {"stiffness", 10}};
    expectRefusedForMemory(manyOf("ropes", rope, 2000), "ropes[");
    EXPECT_NE(refusedField(manyOf("ropes", rope, 2000)).find("].count"), std::string::npos);
}

// Five 1000 x 1000 cloths in a file of under a kilobyte: 5.7 GB by the estimate. Under a 4 GB limit
// on the address space (what the process may take, whatever the machine has) they are refused:
// exit 2, the cloth that passes the limit named with the estimate, and nothing built or written.
TEST(MemoryEstimates, FiveLargeClothsAreRefusedUnderAFourGigabyteLimit)
{
    if (kAddressSanitizer)
        GTEST_SKIP() << "a limit on the address space stops an AddressSanitizer build from starting";
    const auto dir = freshDir("five_cloths");
    std::ofstream(dir / "cloths.json") << manyOf("cloths", kBigCloth, 5);
    const CommandResult r = simUnderLimit(dir / "cloths.json", 4 << 20);
    expectBadInput(r, dir, "a 1000 x 1000 cloth with 1998000 springs needs about 1.13 GB");
    EXPECT_NE(r.err.find("cloths.json: cloths[3]:"), std::string::npos) << r.err;
}

// Rigid bodies count too: a sphere by its draw mesh, a mesh by the size of its file. Under a
// 128 MB limit: 4,000 spheres (180 MB), and 6 bodies of a 1 MB OBJ file (a tetrahedron and a
// comment: 30 MB each by the estimate, which goes by the file's size).
TEST(MemoryEstimates, RigidBodiesAndMeshesBeyondTheMemoryAreRefused)
{
    if (kAddressSanitizer)
        GTEST_SKIP() << "a limit on the address space stops an AddressSanitizer build from starting";
    const auto dir = freshDir("rigid_memory");
    const nlohmann::json sphere = {{"shape", {{"type", "sphere"}, {"radius", 0.1}}}, {"position", {0, 1, 0}}};
    std::ofstream(dir / "spheres.json") << manyOf("rigid_bodies", sphere, 4000);
    CommandResult r = simUnderLimit(dir / "spheres.json", 1 << 17);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(".shape: a sphere needs about 45 KB"), std::string::npos) << r.err;
    std::ofstream obj(dir / "tetra.obj");
    obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n# "
        << std::string(999900, 'x') << "\n";
    obj.close();
    const nlohmann::json mesh = {{"shape", {{"type", "mesh"}, {"path", "tetra.obj"}}}, {"position", {0, 1, 0}}};
    std::ofstream(dir / "meshes.json") << manyOf("rigid_bodies", mesh, 6);
    r = simUnderLimit(dir / "meshes.json", 1 << 17);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(".shape.path: a mesh from a file of 1 MB needs about 30 MB"), std::string::npos) << r.err;
}

struct BoundedFlags {
    std::vector<std::string> args;
    const char* says;
};

void PrintTo(const BoundedFlags& flags, std::ostream* os)
{
    for (const auto& a : flags.args)
        *os << a << ' ';
}

class FlagBounds : public ::testing::TestWithParam<BoundedFlags> {};

// Refused where the flags are checked, before any work: an 8192x8192 PNG took 3 GB to render, and
// a dt of 1e308 s passed the checks and failed in gnuplot with exit 1.
TEST_P(FlagBounds, AreBadInputInOneLineAndWriteNothing)
{
    const auto dir = freshDir("flag_bounds");
    std::vector<std::string> args = GetParam().args;
    for (auto& a : args)
        if (a == "OUT.png" || a == "OUT")
            a = (dir / a).string();
    expectBadInput(runPbaArgv(args), dir, GetParam().says, 0);
}

INSTANTIATE_TEST_SUITE_P(
    Hardening, FlagBounds,
    ::testing::Values(
        BoundedFlags{{"render", "integrators", "--size", "8192x8192", "--out", "OUT.png"},
                     "--size: 8192x8192 is 67.1 million pixels, more than the 16.8 million (4096x4096)"},
        BoundedFlags{{"render", "integrators", "--size", "4097x4096", "--out", "OUT.png"}, "--size: 4097x4096"},
        // A long, thin picture still passes the size check: it is --fps, checked next, that fails.
        BoundedFlags{{"render", "integrators", "--size", "8192x16", "--fps", "0", "--out", "OUT.png"}, "--fps"},
        BoundedFlags{{"compare", "--dt", "1e308", "--out", "OUT"}, "--dt: 1e+308 s is longer than the run (10 s)"},
        BoundedFlags{{"compare", "--duration", "1", "--dt", "0.01,2", "--out", "OUT"}, "--dt: 2 s is longer"},
        BoundedFlags{{"compare", "--duration", "1e308", "--dt", "1e308", "--out", "OUT"},
                     "--duration: 1e+308 s is more than the 1e+300 s a study may plot"},
        BoundedFlags{{"compare", "tennis-racket", "--duration", "0.01", "--dt", "0.1", "--out", "OUT"},
                     "--dt: 0.1 s is longer than the run (0.01 s)"}));
