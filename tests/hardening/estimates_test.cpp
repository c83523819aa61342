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

/// The scene refused for its memory: the field, and a reason naming the estimate (`estimate`, when
/// given: what the reason says the entry needs).
void expectRefusedForMemory(const std::string& json, const std::string& fieldStart, const std::string& estimate = "")
{
    try {
        parseScene(json, "big.json");
        FAIL() << "built it";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.field().rfind(fieldStart, 0), 0u) << e.what();
        EXPECT_NE(e.reason().find("GB of memory available"), std::string::npos) << e.what();
        EXPECT_NE(e.reason().find("needs about"), std::string::npos) << e.what();
        EXPECT_NE(e.reason().find(estimate), std::string::npos) << e.what();
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
    return runShell("ulimit -v " + std::to_string(kilobytes) + "; exec '" + pbaBinary() + "' sim '" +
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

// A cloth's balls list their neighbours along the springs, as many as fit within four radii: a
// 1000 x 1000 cloth 1 m wide whose 1 cm balls overlap ten times over (about 40 GB of lists, where
// its particles and springs take 1.1 GB) is refused for them.
TEST(MemoryEstimates, BallsOfAClothCountTheirNeighbourLists)
{
    nlohmann::json cloth = kBigCloth;
    cloth["radius"] = 0.01;
    expectRefusedForMemory(manyOf("cloths", cloth, 3), "cloths[", "cloth with 1998000 springs needs about 41.3 GB");
}

// A colliding swarm's grains take their contacts' memory besides their own arrays: ten swarms of
// 10^8 colliding grains (about 400 GB by the estimate) are refused for it, naming the first that
// passes the memory available.
TEST(MemoryEstimates, CollidingGrainsCountTheirContacts)
{
    const nlohmann::json grains = {{"count", 100000000}, {"region", {{"min", {-1, 0.1, -1}}, {"max", {1, 1, 1}}}},
                                   {"mass", 0.001}, {"radius", 0.001}, {"collide", true}};
    expectRefusedForMemory(manyOf("swarms", grains, 10), "swarms[", "colliding swarm grains needs about 42.5 GB");
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

namespace {

/// The field and reason a scene is refused for (both empty if it loads).
std::pair<std::string, std::string> refusal(const std::string& json)
{
    try {
        parseScene(json, "bad.json");
    } catch (const SceneError& error) {
        return {error.field(), error.reason()};
    }
    return {};
}

/// A scene in the 4 m cube room [-2, 2] x [0, 4] x [-2, 2] with one rigid body of `shape` at
/// `position`, and `more` keys (an orientation) on the body.
std::string bodyInRoom(const std::string& shape, const std::string& position, const std::string& more = "",
                       const std::string& forces = "[]")
{
    return R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "forces": )" + forces +
           R"(, "rigid_bodies": [{"name": "b", "shape": )" + shape + R"(, "position": )" + position + more + "}]}";
}

const std::string kCube = R"({"type": "box", "size": [0.3, 0.3, 0.3]})";
const std::string kBall = R"({"type": "sphere", "radius": 0.1})";
/// A quarter turn and an eighth of a turn about x, as [w, x, y, z].
const std::string kQuarterTurn = R"(, "orientation": [0.7071067811865476, 0.7071067811865476, 0, 0])";
const std::string kEighthTurn = R"(, "orientation": [0.9238795325112867, 0.3826834323650898, 0, 0])";

} // namespace

// A box whose centre is on the floor was accepted and stayed 0.14 m in it: the whole shape, at its
// orientation, is checked against the floor, the walls and the ceiling. Oracles: a 0.3 m cube's
// half side is 0.15 m; turned 45 degrees about x its lowest edge is 0.15 (cos 45 + sin 45) =
// 0.2121 m below its centre; a sphere reaches its radius every way.
TEST(StatesThatCannotBe, ARigidBodyThroughASurfaceIsRefusedNamingItsPositionAndTheDepth)
{
    const auto dir = freshDir("body_in_floor");
    std::ofstream(dir / "box.json") << bodyInRoom(kCube, "[0, 0, 0]");
    expectBadInput(runPbaArgv({"sim", (dir / "box.json").string(), "--out", (dir / "out.csv").string()}), dir,
                   "rigid_bodies[0].position: the box at its orientation reaches 0.15 m through the floor (y = 0)");
    const auto [field, reason] = refusal(bodyInRoom(kCube, "[0, 0.15, 0]", kEighthTurn));
    EXPECT_EQ(field, "rigid_bodies[0].position");
    EXPECT_NE(reason.find("reaches 0.0621 m through the floor"), std::string::npos) << reason;
    EXPECT_NE(refusal(bodyInRoom(kCube, "[1.9, 2, 0]")).second.find("0.05 m through the wall at x = 2"),
              std::string::npos);
    EXPECT_NE(refusal(bodyInRoom(kCube, "[0, 2, -1.9]")).second.find("0.05 m through the wall at z = -2"),
              std::string::npos);
    EXPECT_NE(refusal(bodyInRoom(kBall, "[0, 3.95, 0]")).second.find("the sphere reaches 0.05 m through the ceiling"),
              std::string::npos);
    // A cylinder lying on its side (a quarter turn about x) reaches its radius down, not half its height.
    const std::string cylinder = R"({"type": "cylinder", "radius": 0.2, "height": 1})";
    EXPECT_EQ(refusal(bodyInRoom(cylinder, "[0, 0.19, 0]", kQuarterTurn)).first, "rigid_bodies[0].position");
    EXPECT_EQ(refusal(bodyInRoom(cylinder, "[0, 0.49, 0]")).first, "rigid_bodies[0].position");
    EXPECT_EQ(refusal(R"({"ground": {"height": 1}, "rigid_bodies": [{"name": "b", "shape": )" + kBall +
                      R"(, "position": [0, 1.05, 0]}]})").first,
              "rigid_bodies[0].position");
    // A mesh by its vertices: this tetrahedron's centre of mass is (1/4, 1/4, 1/4) from its corner
    // at the origin, so that corner is 0.25 m below its centre.
    std::ofstream(dir / "tetra.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    const std::string mesh = R"({"type": "mesh", "path": "tetra.obj"})";
    std::ofstream(dir / "in.json") << bodyInRoom(mesh, "[0, 0.2, 0]");
    std::ofstream(dir / "on.json") << bodyInRoom(mesh, "[0, 0.25, 0]");
    try {
        loadSceneFile(dir / "in.json");
        ADD_FAILURE() << "a mesh 0.05 m through the floor loaded";
    } catch (const SceneError& error) {
        EXPECT_EQ(error.field(), "rigid_bodies[0].position");
        EXPECT_NE(error.reason().find("the mesh at its orientation reaches 0.05 m through the floor"),
                  std::string::npos) << error.reason();
    }
    EXPECT_NO_THROW(loadSceneFile(dir / "on.json"));
}

// A 5 m box in the 4 m room was accepted and thrown out of it: at its orientation it spans more
// than the room along x, whatever its position, so the shape is named. Turned a quarter about x,
// a 1 x 5 x 1 box stands 1 m tall and 5 m deep.
TEST(StatesThatCannotBe, ARigidBodyLargerThanTheRoomIsRefusedNamingItsShape)
{
    const auto [field, reason] = refusal(bodyInRoom(R"({"type": "box", "size": [5, 1, 1]})", "[0, 2, 0]"));
    EXPECT_EQ(field, "rigid_bodies[0].shape");
    EXPECT_NE(reason.find("spans 5 m along x, more than the room's 4 m"), std::string::npos) << reason;
    EXPECT_NE(refusal(bodyInRoom(R"({"type": "box", "size": [1, 5, 1]})", "[0, 2, 0]", kQuarterTurn)).second.find(
                  "spans 5 m along z"),
              std::string::npos);
    EXPECT_EQ(refusal(bodyInRoom(R"({"type": "sphere", "radius": 2.5})", "[0, 2, 0]")).first, "rigid_bodies[0].shape");
}

// Touching is not overlapping: a body resting exactly on the floor, or against a wall, turned or
// not, loads; so does every built-in scene.
TEST(StatesThatCannotBe, RigidBodiesThatTouchASurfaceStayAccepted)
{
    EXPECT_EQ(refusal(bodyInRoom(kCube, "[0, 0.15, 0]")).first, "");
    EXPECT_EQ(refusal(bodyInRoom(kCube, "[1.85, 0.15, -1.85]", kQuarterTurn)).first, "");
    EXPECT_EQ(refusal(bodyInRoom(kCube, "[0, 0.21213203435596428, 0]", kEighthTurn)).first, "");
    EXPECT_EQ(refusal(bodyInRoom(kBall, "[0, 3.9, 1.9]")).first, "");
    EXPECT_EQ(refusal(bodyInRoom(R"({"type": "cylinder", "radius": 0.2, "height": 1})", "[0, 0.2, 0]", kQuarterTurn))
                  .first,
              "");
    EXPECT_EQ(refusal(bodyInRoom(R"({"type": "box", "size": [4, 4, 4]})", "[0, 2, 0]")).first, "");
    for (const std::string& name : builtinSceneNames())
        EXPECT_NO_THROW(loadScene(name)) << name;
}

// The blow dryer's hole: below the floor a body may reach only into the hole's shaft, and not
// through its grille (0.05 m below the floor). A 0.1 m ball centred 0.05 m above the floor cuts
// it in a circle of radius sqrt(0.1^2 - 0.05^2) = 0.0866 m.
TEST(StatesThatCannotBe, BelowTheFloorABodyMayReachOnlyIntoTheDryersHole)
{
    const std::string dryer = R"([{"type": "blow-dryer", "nozzle": [0, 0, 0], "height": 2, "nozzle_radius": 0.2,
                                   "top_radius": 1, "strength": 1}])";
    EXPECT_EQ(refusal(bodyInRoom(kBall, "[0, 0.05, 0]", "", dryer)).first, "");
    EXPECT_EQ(refusal(bodyInRoom(kBall, "[0.11, 0.05, 0]", "", dryer)).first, ""); // 0.1966 m from the axis
    EXPECT_EQ(refusal(bodyInRoom(kBall, "[0, 0.05, 0]")).first, "rigid_bodies[0].position"); // no hole
    const auto [field, reason] = refusal(bodyInRoom(kBall, "[0.12, 0.05, 0]", "", dryer)); // 0.2066 m
    EXPECT_EQ(field, "rigid_bodies[0].position");
    EXPECT_NE(reason.find("through the floor (y = 0) outside its hole"), std::string::npos) << reason;
    EXPECT_NE(refusal(bodyInRoom(kBall, "[0, -0.0, 0]", "", dryer)).second.find(
                  "0.05 m through the grille under the floor's hole (y = -0.05)"),
              std::string::npos);
    // A 0.1 m cube in the shaft, resting on the grille, loads; a corner past the hole's edge does not.
    const std::string small = R"({"type": "box", "size": [0.1, 0.1, 0.1]})";
    EXPECT_EQ(refusal(bodyInRoom(small, "[0, 0, 0]", "", dryer)).first, "");
    EXPECT_EQ(refusal(bodyInRoom(small, "[0.1, 0.01, 0.1]", "", dryer)).first, "rigid_bodies[0].position");
}

// Particles, ropes and cloths are points: each is refused outside the room (and accepted on a
// surface), naming the key that placed it.
TEST(StatesThatCannotBe, ParticlesRopesAndClothsOutsideTheRoomAreRefusedNamingTheKey)
{
    const std::string room = R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, )";
    EXPECT_EQ(refusal(room + R"("particles": [{"name": "p", "position": [0, -0.01, 0]}]})").first,
              "particles[0].position");
    EXPECT_EQ(refusal(room + R"("particles": [{"name": "p", "position": [0, 0, 2]}]})").first, "");
    EXPECT_EQ(refusal(room + R"("ropes": [{"name": "r", "from": [0, 1, 0], "to": [0, 1, 2.5], "count": 5,
                                 "stiffness": 1}]})").first,
              "ropes[0].to");
    EXPECT_EQ(refusal(room + R"("cloths": [{"name": "c", "origin": [1, 3, 0], "across": [1.5, 0, 0],
                                 "down": [0, 0, 1], "columns": 4, "rows": 4, "stiffness": {"structural": 1}}]})").first,
              "cloths[0].origin");
}
