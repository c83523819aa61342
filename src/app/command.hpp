#pragma once
// How the `pba` subcommands plug into the program: each lives in its own file and
// registers itself with CLI11; main() runs the one the user chose and turns
// exceptions into the documented exit codes.
#include <functional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

namespace pba::app {

/// Exit codes (documented in the README).
enum ExitCode : int {
    kExitSuccess = 0,
    kExitFailure = 1,           ///< anything else (I/O failure, missing tool, ...)
    kExitBadInput = 2,          ///< bad scene, option or path
    kExitSimulationFailure = 3, ///< the state stopped being finite
};

/// The default scene of `pba` and its subcommands.
inline constexpr const char* kDefaultScene = "blow-dryer";

/// Bad input from the command line; main() prints it as one line and exits with kExitBadInput.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// An error that is not the user's input; exit kExitFailure.
class RuntimeFailure : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// What a parsed subcommand runs; returns an exit code.
using Action = std::function<int()>;

void addSimCommand(CLI::App& root, Action& selected);
void addFieldCommand(CLI::App& root, Action& selected);
void addRenderCommand(CLI::App& root, Action& selected);
void addViewCommand(CLI::App& root, Action& selected);
void addCompareCommand(CLI::App& root, Action& selected);
void addBenchCommand(CLI::App& root, Action& selected);
void addScenesCommand(CLI::App& root, Action& selected);
void addHelpCommand(CLI::App& root, Action& selected);

/// "unknown command 'simm': did you mean 'sim'? (the commands: sim, ...)": how `pba simm` and
/// `pba help simm` both name a command that is not one of root's.
std::string unknownCommandText(const CLI::App& root, const std::string& name);

/// `pba` with no arguments: the default scene in a window when there is a display,
/// otherwise rendered to an MP4 and a PNG in `directory`.
int runDefault(const std::string& directory);
int renderDefaultScene(const std::string& directory);

} // namespace pba::app
