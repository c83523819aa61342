// The `pba` command: one subcommand per file, errors as one line and a documented exit code.
#include <algorithm>
#include <csignal>
#include <exception>
#include <string>
#include <vector>
#include <iostream>

#include <fmt/format.h>

#include "command.hpp"
#include "io/output_file.hpp"
#include "pba/scene/scene.hpp"
#include "scene_options.hpp"

int main(int argc, char** argv)
{
    using namespace pba::app;
    // Before any thread starts: SIGINT and SIGTERM remove temporaries and stop child programs;
    // a child that stops reading gives EPIPE, not a silent death.
    pba::io::cleanUpOnSignals();
    std::signal(SIGPIPE, SIG_IGN);
    std::signal(SIGXFSZ, SIG_IGN); // past a file size limit a write fails (EFBIG) and is reported

    CLI::App app{"pba: a physics-based animation lab. Particles, integrators and fixed timesteps you can see and "
                 "measure.",
                 "pba"};
    app.footer(fmt::format("\nWithout a COMMAND, pba shows the {0} scene in a window; with no display it renders it\n"
                           "instead, which takes about 20 s, to pba-out/{0}.mp4 and pba-out/{0}.png.\n\n"
                           "Exit status: 0 success, 1 other failure, 2 bad input or usage, 3 simulation failure "
                           "(non-finite state).\nRun `pba help COMMAND` or `pba COMMAND --help` for the options of a "
                           "command.",
                           kDefaultScene));
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

    std::vector<std::string> args(argv + 1, argv + argc);
    std::reverse(args.begin(), args.end()); // CLI11 takes the arguments in reverse order
    try {
        app.parse(args);
    } catch (const CLI::Success& e) { // --help, --version
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        fmt::print(stderr, "pba: error: {}\n", e.what());
        return kExitBadInput;
    }
    if (!selected) // `pba` alone: the default scene, in a window or rendered
        selected = [] { return runDefault("pba-out"); };
    try {
        return selected();
    } catch (const pba::SceneError& e) {
        fmt::print(stderr, "pba: error: {}\n", e.what());
        return kExitBadInput;
    } catch (const UsageError& e) {
        fmt::print(stderr, "pba: error: {}\n", e.what());
        return kExitBadInput;
    } catch (const pba::io::BadOutput& e) {
        fmt::print(stderr, "pba: error: {}\n", e.what());
        return kExitBadInput;
    } catch (const std::exception& e) {
        fmt::print(stderr, "pba: error: {}\n", e.what());
        return kExitFailure;
    }
}
