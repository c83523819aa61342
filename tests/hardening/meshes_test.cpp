// Hardening III: the files a scene names are read safely (only regular files, within limits,
// each once), an OBJ line is read whole or refused naming it, and every message stays one
// honest line: user strings escaped and cut, the failing element and key named.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pba/scene/scene.hpp"
#include "scene/mesh_library.hpp"
#include "scene/obj_reader.hpp"
#include "scene/one_line.hpp"
#include "support/run_command.hpp"

using namespace pba;
using namespace pba::test;
using pba::scene_detail::oneLine;
using pba::scene_detail::oneLineTail;

namespace {

/// A closed tetrahedron, counter-clockwise seen from outside, with its corners scaled by `s`:
/// volume s^3 / 6.
std::string tetrahedron(const std::string& s = "1")
{
    return "v 0 0 0\nv " + s + " 0 0\nv 0 " + s + " 0\nv 0 0 " + s + "\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
}

/// A scene of one rigid body whose shape is the mesh at `path`, written beside the scene.
std::filesystem::path meshScene(const std::filesystem::path& dir, const std::string& path)
{
    const auto scene = dir / "scene.json";
    std::ofstream(scene) << nlohmann::json({{"rigid_bodies",
                                             {{{"name", "m"}, {"shape", {{"type", "mesh"}, {"path", path}}},
                                               {"position", {0, 1, 0}}}}}})
                                .dump();
    return scene;
}

/// The error loading `scene` gives, or nothing if it loads.
std::optional<SceneError> errorLoading(const std::filesystem::path& scene)
{
    try {
        loadScene(scene.string());
    } catch (const SceneError& e) {
        return e;
    }
    return std::nullopt;
}

std::optional<SceneError> errorParsing(const std::string& json)
{
    try {
        parseScene(json, "scene.json");
    } catch (const SceneError& e) {
        return e;
    }
    return std::nullopt;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

} // namespace

// A FIFO used to block the load forever (waiting for a writer): it is refused at once, and the
// program says so in one line with exit 2. `timeout` turns a regression into a failure, not a hang.
TEST(MeshFiles, AFifoIsRefusedWithoutWaitingForAWriter)
{
    const auto dir = freshDir("mesh_fifo");
    ASSERT_EQ(::mkfifo((dir / "pipe.obj").c_str(), 0600), 0);
    const auto scene = meshScene(dir, "pipe.obj");
    const CommandResult r = runShell("timeout 20 " + pbaBinary() + " sim " + scene.string());
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(contains(r.err, "rigid_bodies[0].shape.path")) << r.err;
    EXPECT_TRUE(contains(r.err, "pipe.obj: is not a regular file (a FIFO)")) << r.err;
}

// /dev/zero was read as one endless line until memory ran out, then "has no faces"; a folder
// "has no faces" too, and a missing file said only "cannot be opened".
TEST(MeshFiles, ADeviceAFolderAndAMissingFileAreNamedForWhatTheyAre)
{
    const auto dir = freshDir("mesh_kinds");
    std::filesystem::create_directory(dir / "folder.obj");
    for (const auto& [path, says] : {std::pair{std::string("/dev/zero"), "is not a regular file (a device)"},
                                     std::pair{std::string("folder.obj"), "is a folder"},
                                     std::pair{std::string("missing.obj"), "cannot be opened (No such file"}}) {
        const auto error = errorLoading(meshScene(dir, path));
        ASSERT_TRUE(error) << path;
        EXPECT_EQ(error->field(), "rigid_bodies[0].shape.path") << error->what();
        EXPECT_TRUE(contains(error->reason(), path + ": " + says)) << error->what();
    }
}

// The file's size is checked before a byte is read (a sparse file: 300 MB long, nothing on disk),
// and a line's size as it is read: a file of one 70 KB line is no OBJ file.
TEST(MeshFiles, AFileOrALineTooLongIsRefusedWithTheLimit)
{
    const auto dir = freshDir("mesh_sizes");
    std::ofstream(dir / "huge.obj").close();
    std::filesystem::resize_file(dir / "huge.obj", 300u << 20);
    std::ofstream(dir / "long.obj") << std::string(70 * 1024, 'x') << "\n" << tetrahedron();
    auto error = errorLoading(meshScene(dir, "huge.obj"));
    ASSERT_TRUE(error);
    EXPECT_TRUE(contains(error->reason(), "is 314572800 bytes, more than the 256 MiB")) << error->what();
    error = errorLoading(meshScene(dir, "long.obj"));
    ASSERT_TRUE(error);
    EXPECT_TRUE(contains(error->reason(), "line 1 is longer than 64 KiB")) << error->what();
}

// Four bodies of one 76 MB mesh read it four times and kept four copies of everything made from
// it. The file is read once, however its path is spelt, and the bodies share the shape's
// vertices, contact points and drawn mesh (the same memory), each with its own mass.
TEST(MeshFiles, BodiesNamingOneFileShareOneReadOfIt)
{
    const auto dir = freshDir("mesh_shared");
    std::filesystem::create_directory(dir / "sub");
    std::ofstream(dir / "tetra.obj") << tetrahedron();
    std::ofstream(dir / "other.obj") << tetrahedron();
    std::ofstream(dir / "four.json") << R"({"rigid_bodies": [
        {"name": "a", "shape": {"type": "mesh", "path": "tetra.obj"}, "position": [0, 1, 0]},
        {"name": "b", "shape": {"type": "mesh", "path": "./tetra.obj"}, "density": 500, "position": [2, 1, 0]},
        {"name": "c", "shape": {"type": "mesh", "path": "sub/../tetra.obj"}, "mass": 3, "position": [4, 1, 0]},
        {"name": "d", "shape": {"type": "mesh", "path": ")" + (dir / "tetra.obj").string() +
                                        R"("}, "position": [6, 1, 0]},
        {"name": "e", "shape": {"type": "mesh", "path": "other.obj"}, "position": [8, 1, 0]}]})";
    const Scene scene = loadScene((dir / "four.json").string());
    const auto body = [&](std::size_t i) -> const RigidBody& {
        return static_cast<const RigidBody&>(scene.world.body(i));
    };
    for (std::size_t i = 1; i < 4; ++i) {
        EXPECT_EQ(body(i).getShape().vertices.data(), body(0).getShape().vertices.data()) << i;
        EXPECT_EQ(body(i).getContactPoints().data(), body(0).getContactPoints().data()) << i;
        EXPECT_EQ(body(i).getMesh().vertices().data(), body(0).getMesh().vertices().data()) << i;
    }
    EXPECT_NE(body(4).getShape().vertices.data(), body(0).getShape().vertices.data()); // another file
    // Each its own mass: the tetrahedron's volume is 1/6 m^3.
    EXPECT_NEAR(body(0).getMass(), 1000.0 / 6.0, 1e-9);
    EXPECT_NEAR(body(1).getMass(), 500.0 / 6.0, 1e-9);
    EXPECT_EQ(body(2).getMass(), 3.0);
    EXPECT_NEAR(body(2).getInertiaBody()[0][0], 3.0 / (1000.0 / 6.0) * body(0).getInertiaBody()[0][0], 1e-12);

    scene_detail::MeshLibrary library;
    library.body(dir / "tetra.obj");
    library.body(dir / "sub" / ".." / "tetra.obj");
    EXPECT_EQ(library.filesRead(), 1u);
    library.body(dir / "other.obj");
    EXPECT_EQ(library.filesRead(), 2u);
}

// "cube.obj", a NUL byte and "ignored" opened cube.obj: the system ends a path at a NUL.
TEST(ObjFiles, APathWithANulByteIsRefused)
{
    const auto dir = freshDir("mesh_nul");
    std::ofstream(dir / "tetra.obj") << tetrahedron();
    const auto error = errorLoading(meshScene(dir, std::string("tetra.obj\0ignored", 17)));
    ASSERT_TRUE(error);
    EXPECT_EQ(error->field(), "rigid_bodies[0].shape.path");
    EXPECT_TRUE(contains(error->reason(), "NUL byte (at offset 9)")) << error->what();
}

// A byte order mark made the first line's statement "\xEF\xBB\xBFv", silently dropping the first
// vertex ("vertex 4 does not exist (there are 3 so far)").
TEST(ObjFiles, AByteOrderMarkIsSkipped)
{
    const scene_detail::ObjMesh mesh = scene_detail::parseObj("\xEF\xBB\xBF" + tetrahedron());
    EXPECT_EQ(mesh.vertices.size(), 4u);
    EXPECT_EQ(mesh.triangles.size(), 12u);
}

struct BadObj {
    const char* text;
    const char* says;
};

void PrintTo(const BadObj& bad, std::ostream* os) { *os << bad.says; }

class BadObjLines : public testing::TestWithParam<BadObj> {};

// `1abc` and `4.9xyz` were read as vertices 1 and 4, `v 0 0 0 junk` as a vertex: each line is
// now read whole, or refused naming it.
TEST_P(BadObjLines, AreRefusedNamingTheLine)
{
    try {
        scene_detail::parseObj(GetParam().text);
        FAIL() << "read: " << GetParam().text;
    } catch (const std::runtime_error& e) {
        EXPECT_TRUE(contains(e.what(), GetParam().says)) << e.what();
    }
}

INSTANTIATE_TEST_SUITE_P(
    ObjFiles, BadObjLines,
    testing::Values(BadObj{"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1abc 2 3\n", "line 4: '1abc' is not a corner"},
                    BadObj{"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 4.9xyz\n", "line 5: '4.9xyz' is not a corner"},
                    BadObj{"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", "line 4: '1/1/1/1' is not a corner"},
                    BadObj{"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/x 2 3\n", "line 4: '1/x' is not a corner"},
                    BadObj{"v 0 0 0 junk\n", "line 1: a vertex is three numbers"},
                    BadObj{"v 0 0\n", "line 1: a vertex is three numbers"},
                    BadObj{"# a comment\nv 0 0 1e999\n", "line 2: '1e999' is not a finite number"},
                    BadObj{"v 0 0 nan\n", "line 1: 'nan' is not a finite number"},
                    BadObj{"v 0 0 0x\n", "line 1: '0x' is not a finite number"},
                    BadObj{"v 0 0 0\nv 1 0 0\nf 1 2\n", "line 3: a face needs at least three vertices"},
                    BadObj{"vt 0 0\n", "has no faces"}));

// What OBJ writers put in a line still loads: CRLF, tabs, a leading '+', v/vt/vn and v//vn
// corners, negative (relative) indices, a vertex colour, and statements pba does not use.
TEST(ObjFiles, WhatWritersWriteStillLoads)
{
    const scene_detail::ObjMesh mesh =
        scene_detail::parseObj("o tetra\r\nv 0 0 0 1 0 0\r\nv\t+1 0 0\r\nv 0 1.0e0 0\r\nv 0 0 1\r\nvn 0 0 1\r\n"
                               "s off\r\nf 1/1/1 3/1/1 2/1/1\r\nf 1//1 2//1 4//1\r\nf 1/1 4/1 3/1\r\nf -3 -2 -1\r\n");
    EXPECT_EQ(mesh.vertices.size(), 4u);
    EXPECT_EQ(mesh.vertices[1], dvec3(1.0, 0.0, 0.0));
    ASSERT_EQ(mesh.triangles.size(), 12u);
    EXPECT_EQ(mesh.triangles[9], 1u); // -3 of four: the second vertex
}

// The file a scene names may be anyone's (a path may leave the scene's folder, and does here):
// a message quotes at most a short, escaped word of the line, never the line.
TEST(ObjFiles, AnErrorQuotesOnlyAShortEscapedWordOfTheLine)
{
    const auto dir = freshDir("mesh_quote");
    std::filesystem::create_directories(dir / "a" / "b");
    const std::string secret = "password=hunter2-and-the-rest-of-a-long-secret-line";
    std::ofstream(dir / "secret.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \x1b[31m" << secret << "\n";
    std::ofstream(dir / "tetra.obj") << tetrahedron();
    EXPECT_FALSE(errorLoading(meshScene(dir / "a" / "b", "../../tetra.obj"))); // outside the folder: allowed
    EXPECT_FALSE(errorLoading(meshScene(dir / "a", (dir / "tetra.obj").string())));
    const auto error = errorLoading(meshScene(dir / "a" / "b", "../../secret.obj"));
    ASSERT_TRUE(error);
    const std::string what = error->what();
    EXPECT_TRUE(contains(what, "line 4: '\\x1b[31mpassword=hunter2... (")) << what;
    EXPECT_FALSE(contains(what, "rest-of-a-long")) << what;
    EXPECT_EQ(what.find('\x1b'), std::string::npos) << what;
}

TEST(Messages, OneLineEscapesControlCharactersAndCutsLongStrings)
{
    EXPECT_EQ(oneLine("a\nb\tc\rd\x01" "e\x7f"), "a\\nb\\tc\\rd\\x01e\\x7f");
    EXPECT_EQ(oneLine("next\xc2\x85line"), "next\\u0085line"); // U+0085, NEL: a line break to some
    EXPECT_EQ(oneLine("caf\xc3\xa9"), "caf\xc3\xa9");            // UTF-8 text stays as it is
    EXPECT_EQ(oneLine(std::string(100, 'a')), std::string(80, 'a') + "... (100 bytes)");
    // A cut never splits a character: 41 two-byte characters, 80 bytes kept of 82.
    std::string accents;
    for (int i = 0; i < 41; ++i)
        accents += "\xc3\xa9";
    EXPECT_EQ(oneLine(accents), accents.substr(0, 80) + "... (82 bytes)");
    EXPECT_EQ(oneLine(std::string(79, 'a') + "\n"), std::string(79, 'a') + "... (80 bytes)"); // "\n" is 2 shown
    EXPECT_EQ(oneLineTail(std::string(100, 'a') + "!\n", 10), "(102 bytes) ...aaaaaaa!\\n");
    EXPECT_EQ(oneLineTail("short\n"), "short\\n");
}

// A newline in a name, a key or a path broke the one-line rule; a 1 MB string was echoed whole.
TEST(Messages, UserStringsInMessagesAreEscapedAndCut)
{
    const std::string mega(1 << 20, 'n');
    const std::vector<std::string> scenes{
        R"({"particles": [{"name": "a", "position": [0, 1, 0]}], "forces": [{"type": "spring", "particle": "a\nb",
            "anchor": [0, 0, 0], "stiffness": 1}]})",
        R"({"bad\nkey": 1})",
        R"({"rigid_bodies": [{"name": "a", "shape": {"type": "sph\nere"}, "position": [0, 1, 0]}]})",
        R"({"particles": [{"name": ")" + mega + R"(", "position": [0, 1, 0]}, {"name": ")" + mega +
            R"(", "position": [0, 1, 0]}]})",
        R"({")" + mega + R"(": 1})",
        R"({"forces": [{"type": ")" + mega + R"("}]})",
        R"({"particles": [{"name": "a", "position": [0, 1, 0], "integrator": ")" + mega + R"("}]})",
        R"({"name": ")" + mega + "\n\"}", // a raw newline in a string: malformed, and the parser quotes it all
    };
    std::vector<SceneError> errors;
    for (const std::string& json : scenes) {
        const auto error = errorParsing(json);
        ASSERT_TRUE(error) << json.substr(0, 200);
        const std::string what = error->what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what.substr(0, 300);
        EXPECT_LT(what.size(), 600u) << what.substr(0, 300);
        errors.push_back(*error);
    }
    EXPECT_TRUE(contains(errors[0].what(), "no particle or rigid body named 'a\\nb'")) << errors[0].what();
    EXPECT_EQ(errors[1].field(), "bad\\nkey");
    EXPECT_TRUE(contains(errors[2].what(), "unknown shape 'sph\\nere'")) << errors[2].what();
    EXPECT_TRUE(contains(errors[3].what(), "already named 'nnnn")) << errors[3].what();
    EXPECT_TRUE(contains(errors[3].what(), "n... (1048576 bytes)'")) << errors[3].what();
    EXPECT_TRUE(contains(errors[7].what(), "last read: '(1048585 bytes) ...nnn")) << errors[7].what();
    try { // the path of a scene file, or what was typed for one
        loadScene(mega + "\n.json");
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        EXPECT_LT(std::string(e.what()).size(), 600u);
    }
}

// The program's edge keeps every error to one line, whatever a path or an argument holds.
TEST(Messages, TheProgramPrintsEveryErrorAsOneLine)
{
    using Case = std::pair<std::vector<std::string>, std::string>;
    for (const auto& [args, says] : {Case{{"sim", "no\nsuch\x01.json"}, "no\\nsuch\\x01.json: (file): no such file"},
                                     Case{{"si\nm"}, "unknown command 'si\\nm'"}}) {
        const CommandResult r = runPbaArgv(args);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_TRUE(contains(r.err, says)) << r.err;
    }
}

// The number being parsed had not been counted in its array yet: 1e999 in position[2] was
// blamed on position[1], and in position[0] on position.
TEST(Messages, ANumberThatOverflowsIsBlamedOnItsElement)
{
    for (const auto& [json, field] :
         {std::pair{R"({"particles": [{"name": "a", "position": [0, 1, 1e999]}]})", "particles[0].position[2]"},
          std::pair{R"({"particles": [{"name": "a", "position": [1e999, 1, 0]}]})", "particles[0].position[0]"},
          std::pair{R"({"ropes": [], "particles": [{"name": "a", "position": [0, 1, 0]}, 1e999]})", "particles[1]"},
          std::pair{R"({"gravity": [0, 1e999, 0]})", "gravity[1]"}, std::pair{R"({"dt": 1e999})", "dt"}}) {
        const auto error = errorParsing(json);
        ASSERT_TRUE(error) << json;
        EXPECT_EQ(error->field(), field) << error->what();
        EXPECT_TRUE(contains(error->reason(), "number overflow")) << error->what();
    }
}

struct ExtremeSize {
    std::string json; ///< a rigid body's "shape" and mass keys
    const char* field;
    const char* says;
};

void PrintTo(const ExtremeSize& bad, std::ostream* os) { *os << bad.field << ": " << bad.says; }

class ExtremeSizes : public testing::TestWithParam<ExtremeSize> {};

// Sizes whose mass or inertia overflow or underflow were blamed on `density` ("gives no usable
// mass properties") even with no density given: the key that makes the body extreme is named.
TEST_P(ExtremeSizes, AreBlamedOnTheKeyThatMakesThem)
{
    const auto dir = freshDir("mesh_extremes");
    std::ofstream(dir / "huge.obj") << tetrahedron("1e120");   // a volume of 1e360: overflows
    std::ofstream(dir / "big.obj") << tetrahedron("1e60");     // its inertia overflows
    std::ofstream(dir / "tiny.obj") << tetrahedron("1e-120");  // a volume of 1e-360: underflows
    std::ofstream(dir / "scene.json") << R"({"rigid_bodies": [{"name": "r", "position": [0, 1, 0], )" << GetParam().json
                                      << "}]}";
    const auto error = errorLoading(dir / "scene.json");
    ASSERT_TRUE(error) << GetParam().json;
    EXPECT_EQ(error->field(), GetParam().field) << error->what();
    EXPECT_TRUE(contains(error->reason(), GetParam().says)) << error->what();
}

INSTANTIATE_TEST_SUITE_P(
    MassProperties, ExtremeSizes,
    testing::Values(
        ExtremeSize{R"("shape": {"type": "box", "size": [1e200, 1, 1]})", "rigid_bodies[0].shape.size", "too large"},
        ExtremeSize{R"("shape": {"type": "box", "size": [1e-120, 1e-120, 1e-120]})", "rigid_bodies[0].shape.size",
                    "too small"},
        ExtremeSize{R"("shape": {"type": "sphere", "radius": 1e-120})", "rigid_bodies[0].shape.radius", "too small"},
        ExtremeSize{R"("shape": {"type": "sphere", "radius": 1e120}, "density": 1)", "rigid_bodies[0].shape.radius",
                    "too large"},
        ExtremeSize{R"("shape": {"type": "cylinder", "radius": 1e-200, "height": 1})",
                    "rigid_bodies[0].shape.radius", "too small"},
        ExtremeSize{R"("shape": {"type": "cylinder", "radius": 1, "height": 1e300})",
                    "rigid_bodies[0].shape.height", "too large"},
        ExtremeSize{R"("shape": {"type": "mesh", "path": "huge.obj"})", "rigid_bodies[0].shape.path", "too large"},
        ExtremeSize{R"("shape": {"type": "mesh", "path": "big.obj"})", "rigid_bodies[0].shape.path", "too large"},
        ExtremeSize{R"("shape": {"type": "mesh", "path": "tiny.obj"})", "rigid_bodies[0].shape.path", "too small"},
        // A size fine at 1 kg/m^3 but not at the default 1000: the size, since no density was given.
        ExtremeSize{R"("shape": {"type": "sphere", "radius": 1e20})", "rigid_bodies[0].shape.radius",
                    "at the default density"},
        // An ordinary size: the density or mass given is what cannot be.
        ExtremeSize{R"("shape": {"type": "sphere", "radius": 1e20}, "density": 1e6)", "rigid_bodies[0].density",
                    "gives no usable mass properties"},
        ExtremeSize{R"("shape": {"type": "sphere", "radius": 1e-20}, "density": 1e-300)", "rigid_bodies[0].density",
                    "gives no usable mass properties"},
        ExtremeSize{R"("shape": {"type": "mesh", "path": "tiny.obj"}, "density": 1e-300)", "rigid_bodies[0].shape.path",
                    "too small"},
        ExtremeSize{R"("shape": {"type": "box", "size": [1, 1, 1]}, "mass": 1e-320)", "rigid_bodies[0].mass",
                    "gives no usable mass properties"}));
