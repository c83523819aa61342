// What a student reads first: `pba --help`, each command's --help, `pba help`, `pba scenes`,
// `pba --version`. Every scene-taking command names the built-in scenes, and no option shows
// CLI11's own placeholders (INT:INT in [16 - 2000], X,Y,Z x 3, TEXT) instead of words.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pba/scene/scene.hpp"
#include "support/run_command.hpp"

using namespace pba::test;

namespace {

const std::vector<std::string> kSceneCommands{"", "sim", "field", "render", "view", "compare"};
const std::vector<std::string> kCommands{"", "sim", "field", "render", "view", "compare", "bench", "scenes", "help"};

std::string helpOf(const std::string& command)
{
    const CommandResult r = runPba(command.empty() ? "--help" : command + " --help");
    EXPECT_EQ(r.exitCode, 0) << command << ": " << r.err;
    EXPECT_EQ(r.err, "") << command;
    return r.out;
}

} // namespace

TEST(PbaHelp, EverySceneTakingCommandListsTheBuiltinScenesWithTheirSummaries)
{
    for (const auto& command : kSceneCommands) {
        const std::string help = helpOf(command);
        for (const auto& name : pba::builtinSceneNames()) {
            const std::regex line("\n  " + name + " +" + std::regex_replace(pba::builtinSceneSummary(name),
                                                                             std::regex(R"([.^$|()\[\]{}*+?\\])"),
                                                                             R"(\$&)") + "\n");
            EXPECT_TRUE(std::regex_search(help, line)) << "pba " << command << " --help lacks " << name << "\n" << help;
        }
    }
}

TEST(PbaHelp, NoOptionShowsCli11Placeholders)
{
    for (const auto& command : kCommands) {
        const std::string help = helpOf(command);
        for (const char* leak : {"INT", "FLOAT", "TEXT", "UINT", " in [", " x 3", " x 2", "=blow-dryer"})
            EXPECT_EQ(help.find(leak), std::string::npos) << "pba " << command << " --help shows '" << leak << "'\n"
                                                           << help;
    }
}

TEST(PbaHelp, FitsAHundredColumnsWithEachOptionsNameBesideItsDescription)
{
    for (const auto& command : kCommands) {
        const std::string help = helpOf(command);
        std::size_t start = 0;
        for (std::size_t end = help.find('\n'); end != std::string::npos; start = end + 1, end = help.find('\n', start))
            EXPECT_LE(end - start, 100u) << "pba " << command << " --help: " << help.substr(start, end - start);
        // CLI11 prints a flag's exclusions between its name and its description, and the
        // description on a line of its own; pba's descriptions say it in words.
        for (const char* list : {"Excludes:", "Needs:"})
            EXPECT_EQ(help.find(list), std::string::npos) << "pba " << command << " --help\n" << help;
    }
}

TEST(PbaHelp, HelpCommandPrintsWhatHelpFlagPrints)
{
    for (const auto& command : kCommands) {
        const CommandResult word = runPba("help " + command);
        EXPECT_EQ(word.exitCode, 0) << command << ": " << word.err;
        EXPECT_EQ(word.out, helpOf(command)) << "pba help " << command;
    }
    const CommandResult unknown = runPba("help simulate");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("help: unknown command 'simulate'"), std::string::npos) << unknown.err;
    EXPECT_EQ(unknown.out, "");
}

// docs/commands.md promises every command's help ends in examples (`scenes` and `help` take
// nothing worth one).
TEST(PbaHelp, EveryCommandsHelpEndsInExamples)
{
    for (const char* command : {"sim", "field", "render", "view", "compare", "bench"}) {
        const std::string help = helpOf(command);
        const auto at = help.find("\nExamples:\n  pba " + std::string(command) + " ");
        EXPECT_NE(at, std::string::npos) << "pba " << command << " --help\n" << help;
    }
}

namespace {

/// The line of `help` that describes `option`, with the lines its description wraps onto.
std::string optionHelp(const std::string& help, const std::string& option)
{
    const std::size_t at = help.find("\n  " + option + " ");
    const std::size_t end = at == std::string::npos ? at : help.find("\n  --", at + 1);
    return at == std::string::npos ? std::string() : help.substr(at, end - at);
}

/// Every key of `object`, and of the objects in its arrays, at any depth.
void collectKeys(const nlohmann::json& object, std::set<std::string>& keys)
{
    for (const auto& [key, value] : object.items()) {
        if (object.is_object())
            keys.insert(key);
        if (value.is_structured())
            collectKeys(value, keys);
    }
}

} // namespace

// `field --json`'s help named two of its three keys, and `bench --json`'s one of two: the help
// and docs/commands.md now name every key the commands write.
TEST(PbaHelp, JsonOutputsAreDescribedByTheHelpAndTheDocs)
{
    const std::string docs = readFile(sourceDir() / "docs" / "commands.md");
    const CommandResult field = runPba("field blow-dryer --at 0,1,0 --json");
    ASSERT_EQ(field.exitCode, 0) << field.err;
    std::set<std::string> keys;
    collectKeys(nlohmann::json::parse(field.out), keys);
    const std::string fieldHelp = optionHelp(helpOf("field"), "--json");
    for (const std::string& key : keys) {
        EXPECT_NE(fieldHelp.find("\"" + key + "\""), std::string::npos) << key << "\n" << fieldHelp;
        EXPECT_NE(docs.find("\"" + key + "\""), std::string::npos) << key;
    }
    const CommandResult phases = runPba("bench --phases --sizes 1e3 --quick --json");
    ASSERT_EQ(phases.exitCode, 0) << phases.err;
    keys.clear();
    collectKeys(nlohmann::json::parse(phases.out), keys);
    for (const std::string& key : keys)
        EXPECT_NE(docs.find("\"" + key + "\""), std::string::npos) << key;
    const std::string benchHelp = optionHelp(helpOf("bench"), "--json");
    for (const char* key : {"\"machine\"", "\"results\"", "\"layout\""})
        EXPECT_NE(benchHelp.find(key), std::string::npos) << key << "\n" << benchHelp;
}

// Every option a command's help lists is in docs/commands.md, or, for view's and render's, in
// docs/viewer.md, where commands.md sends them: render's --arrows and --no-trails were in neither.
TEST(PbaHelp, EveryOptionIsInTheDocs)
{
    const std::string commands = readFile(sourceDir() / "docs" / "commands.md");
    const std::string viewer = readFile(sourceDir() / "docs" / "viewer.md");
    const std::regex option(R"(\n  (?:-h,)?(--[a-z-]+))");
    for (const auto& command : kCommands) {
        const std::string help = helpOf(command);
        const bool drawing = command == "view" || command == "render";
        for (auto it = std::sregex_iterator(help.begin(), help.end(), option); it != std::sregex_iterator(); ++it) {
            const std::regex named("(^|[^a-z-])" + (*it)[1].str() + "(?![a-z-])"); // --phase, not --phases
            EXPECT_TRUE(std::regex_search(commands, named) || (drawing && std::regex_search(viewer, named)))
                << "pba " << command << " " << (*it)[1];
        }
    }
}

TEST(PbaHelp, VersionIsOneLine)
{
    const CommandResult r = runPba("--version");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::regex_match(r.out, std::regex(R"(pba \d+\.\d+\.\d+\n)"))) << r.out;
}

// CLI11 printed the version and dropped whatever came with it.
TEST(PbaHelp, VersionWithOtherWordsIsRefused)
{
    for (const std::string args : {"--version extra", "--version sim", "bogus --version"}) {
        const CommandResult r = runPba(args);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(r.err.rfind("pba: error: --version: takes nothing else, got '", 0), 0u) << r.err;
        EXPECT_EQ(r.out, "") << r.out;
    }
}

TEST(PbaHelp, ScenesCommandListsEveryBuiltinSceneOnALineOfItsOwn)
{
    const CommandResult r = runPba("scenes");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const auto names = pba::builtinSceneNames();
    for (const auto& name : names)
        EXPECT_NE(r.out.find("\n  " + name + " "), std::string::npos) << name << "\n" << r.out;
    // A heading and one line per scene, each short enough for a terminal.
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), static_cast<long>(names.size()) + 1) << r.out;
    std::size_t start = 0;
    for (std::size_t end; (end = r.out.find('\n', start)) != std::string::npos; start = end + 1)
        EXPECT_LE(end - start, 100u) << r.out.substr(start, end - start);
}

// Bare `pba` without a display spends about 20 s rendering: the help says so, and where to.
TEST(PbaHelp, TopHelpSaysWhatBarePbaDoes)
{
    const std::string help = helpOf("");
    for (const char* expected : {"pba-out/blow-dryer.mp4", "about 20 s", "pba help COMMAND", "Exit status"})
        EXPECT_NE(help.find(expected), std::string::npos) << expected << "\n" << help;
    for (const char* command : {"scenes", "help"})
        EXPECT_NE(help.find(std::string("\n  ") + command + " "), std::string::npos) << command;
}

// The README's examples write under pba-out/, which a fresh clone does not have: a missing last
// folder is made, a path of missing folders is still refused (a typo, most likely).
TEST(PbaOutputs, AMissingLastFolderIsMadeButNotAPathOfThem)
{
    const auto dir = freshDir("out_folder");
    RunOptions inDir;
    inDir.workDir = dir;
    CommandResult r = runPbaArgv({"sim", "bouncing-cube", "--duration", "0.1", "--out", "pba-out/run.csv"}, inDir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "pba-out/run.csv"));
    std::filesystem::remove_all(dir / "pba-out");
    r = runPbaArgv({"compare", "--duration", "1", "--out", "pba-out/study"}, inDir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "pba-out/study/report.md"));

    r = runPbaArgv({"sim", "bouncing-cube", "--duration", "0.1", "--out", "typo/pba-out/run.csv"}, inDir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("the folder typo does not exist"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "typo"));
    // A bad scene writes nothing, not even the folder.
    r = runPbaArgv({"sim", "no-such-scene", "--out", "new/run.csv"}, inDir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_FALSE(std::filesystem::exists(dir / "new"));
}
