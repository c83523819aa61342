// The `pba` command: one subcommand per file, errors as one line and a documented exit code.
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <vector>
#include <iostream>

#include <fmt/format.h>

#include "command.hpp"
#include "help_formatter.hpp"
#include "parse_errors.hpp"
#include "io/output_file.hpp"
#include "pba/blow_up_watch.hpp"
#include "pba/scene/scene.hpp"
#include "scene/one_line.hpp"
#include "scene_options.hpp"

namespace {

/// What an empty positional should have held, for its message.
std::string positionalWant(const std::string& name)
{
    if (name == "SCENE")
        return "a scene name or a file";
    if (name == "COMMAND")
        return "a command's name";
    return "a value";
}

/// An empty word (`--dt ""` or `--dt=`, a script's unset variable) is refused: CLI11 reads it as
/// no value at all, or as 0, and `pba sim rope --dt ""` ran with the scene's own dt. It is named
/// as what the words before it make it: an option's value, or a positional of the command (SCENE
/// in `pba sim ""`), counted past the options and their values.
std::optional<std::string> emptyArgumentText(const CLI::App& app, const std::vector<std::string>& args)
{
    const CLI::App* command = nullptr; // once its name is read
    std::size_t positionals = 0;       // the command's words so far that are neither options nor their values
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& word = args[i];
        if (word.size() > 2 && word.rfind("--", 0) == 0 && word.back() == '=')
            return fmt::format("{}: empty; give it a value", word.substr(0, word.size() - 1));
        if (word.size() > 2 && word.rfind("--", 0) == 0 && word.find('=') == std::string::npos) {
            // The next word is the option's value, unless the option is a known flag or the word
            // is an option itself (as CLI11 reads it).
            const CLI::Option* option = (command ? command : &app)->get_option_no_throw(word);
            if (option && option->get_items_expected_max() == 0)
                continue;
            if (i + 1 < args.size() && args[i + 1].empty())
                return fmt::format("{}: empty; give it a value", word);
            if (i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0)
                ++i;
            continue;
        }
        if (word.empty()) {
            if (command) {
                const auto named = command->get_options([](const CLI::Option* o) { return o->get_positional(); });
                if (positionals < named.size()) {
                    const std::string name = named[positionals]->get_name();
                    return fmt::format("{}: empty; give it {}", name, positionalWant(name));
                }
            }
            return std::string("an empty argument: give it a value, or leave it out");
        }
        if (word.size() > 1 && word[0] == '-')
            continue; // a short flag (-h)
        if (!command) {
            const auto found = app.get_subcommands([&](const CLI::App* c) { return c->check_name(word); });
            if (!found.empty()) {
                command = found.front();
                continue;
            }
        }
        ++positionals;
    }
    return std::nullopt;
}

/// Every error is one line on stderr, whatever a path, a flag or a name it quotes holds.
void printError(std::string_view what)
{
    fmt::print(stderr, "pba: error: {}\n", pba::scene_detail::oneLine(what, pba::scene_detail::kWhole));
}

/// Runs the command the arguments name; returns its exit status.
int run(int argc, char** argv)
{
    using namespace pba::app;
    // Before any thread starts: SIGINT, SIGTERM and SIGHUP remove temporaries and stop child
    // programs; a child that stops reading gives EPIPE, not a silent death.
    pba::io::cleanUpOnSignals();
    std::signal(SIGPIPE, SIG_IGN);
    std::signal(SIGXFSZ, SIG_IGN); // past a file size limit a write fails (EFBIG) and is reported

    CLI::App app{"pba: a physics-based animation lab. Particles, integrators and fixed timesteps you can see and "
                 "measure.",
                 "pba"};
    app.formatter(std::make_shared<HelpFormatter>()); // before the commands: each copies it
    app.footer(fmt::format("\nWithout a COMMAND, pba shows the {0} scene in a window; with no display it renders it\n"
                           "instead, which takes about 20 s, to pba-out/{0}.mp4 and pba-out/{0}.png.\n\n"
                           "Exit status: 0 success, 1 other failure, 2 bad input or usage, 3 simulation failure:\n"
                           "the run blew up (a state not finite, a rigid body's centre inside a wall, or the\n"
                           "energy {1:g} times its scale above its start and its sources' work).\nRun `pba help COMMAND` or `pba COMMAND --help` for the options of a "
                           "command.",
                           kDefaultScene, pba::BlowUpWatch::kEnergyGrowthLimit));
    listScenesInHelp(app);
    app.set_version_flag("--version", fmt::format("pba {}", PBA_VERSION), "Print the version and exit");
    app.require_subcommand(0, 1);
    Action selected;
    addSimCommand(app, selected);
    addFieldCommand(app, selected);
    addRenderCommand(app, selected);
    addViewCommand(app, selected);
    addCompareCommand(app, selected);
    addBenchCommand(app, selected);
    addScenesCommand(app, selected);
    addHelpCommand(app, selected);

    const std::vector<std::string> typed(argv + 1, argv + argc);
    if (const auto empty = emptyArgumentText(app, typed)) {
        printError(*empty);
        return kExitBadInput;
    }
    // CLI11 answers --version wherever it stands before a command, and drops the other words.
    const auto command = std::find_if(typed.begin(), typed.end(), [&](const std::string& w) {
        return !app.get_subcommands([&](const CLI::App* c) { return c->check_name(w); }).empty();
    });
    if (typed.size() > 1 && std::find(typed.begin(), command, "--version") != command) {
        const auto other = std::find_if(typed.begin(), typed.end(), [](const std::string& w) { return w != "--version"; });
        printError(fmt::format("--version: takes nothing else, got '{}'", other == typed.end() ? "--version" : *other));
        return kExitBadInput;
    }
    std::vector<std::string> args(typed.rbegin(), typed.rend()); // CLI11 takes the arguments in reverse order
    try {
        app.parse(args);
    } catch (const CLI::Success& e) { // --help, --version
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        printError(pba::app::parseErrorText(e, app, typed));
        return kExitBadInput;
    }
    if (!selected) // `pba` alone: the default scene, in a window or rendered
        selected = [] { return runDefault("pba-out"); };
    try {
        return selected();
    } catch (const pba::SceneError& e) {
        printError(e.what());
        return kExitBadInput;
    } catch (const UsageError& e) {
        printError(e.what());
        return kExitBadInput;
    } catch (const pba::io::BadOutput& e) {
        printError(e.what());
        return kExitBadInput;
    } catch (const std::exception& e) {
        printError(e.what());
        return kExitFailure;
    }
}

/// Results reach standard output through stdio's buffer, so a write that fails (a full disk,
/// /dev/full, a reader gone) may show only here, after the command returned 0: it is reported
/// then and the status is 1, a failed write's. An earlier error keeps its own status and line.
int finishStandardOutput(int status)
{
    errno = 0;
    const bool flushFailed = std::fflush(stdout) != 0;
    const int error = errno;
    std::cout.flush();
    if (!flushFailed && !std::ferror(stdout) && !std::cout.fail())
        return status;
    if (status != pba::app::kExitSuccess)
        return status;
    // A reader that stopped reading (`pba scenes | head -3`) wanted no more: no message for it.
    if (flushFailed && error == EPIPE)
        return pba::app::kExitFailure;
    // A write that failed before the last flush left no errno behind: stdio dropped its buffer.
    printError(fmt::format("standard output: {}", flushFailed && error != 0 ? std::strerror(error) : "a write failed"));
    return pba::app::kExitFailure;
}

} // namespace

int main(int argc, char** argv) { return finishStandardOutput(run(argc, argv)); }
