// Hardening III: every message stays one honest line, what the user wrote in it escaped and cut.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "pba/scene/scene.hpp"
#include "scene/one_line.hpp"
#include "support/run_command.hpp"

using namespace pba;
using namespace pba::test;
using pba::scene_detail::oneLine;
using pba::scene_detail::oneLineTail;

namespace {

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
