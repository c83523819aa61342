#pragma once
// The options that override a scene, shared by every subcommand that runs one.
#include <cstdint>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "pba/scene/scene.hpp"

namespace pba::app {

struct SceneOptions {
    std::string scene;
    std::optional<double> dt;
    std::optional<double> duration;
    std::optional<std::string> integrator;
    std::optional<std::string> collision;
    std::optional<int> substeps;
};

/// Adds the positional SCENE (with `defaultScene`) and --dt, --duration, --integrator, --substeps, --collision,
/// and the list of built-in scenes to the command's help.
void addSceneOptions(CLI::App& command, SceneOptions& options, const std::string& defaultScene);

/// The positional SCENE alone (for commands without the overrides), and the scene list in the help.
void addScenePositional(CLI::App& command, std::string& scene, const std::string& defaultScene);

/// "Built-in scenes ...:" and one line per scene with its summary, for help texts and `pba scenes`.
std::string builtinSceneList();

/// Puts builtinSceneList() at the end of the command's help, before its own footer.
void listScenesInHelp(CLI::App& command);

/// The integrator an --integrator flag names; throws UsageError naming the flag and the names.
Integrator integratorFlag(const std::string& name);

/// The most steps one run may take: beyond it a run is a typo (dt 1e-12), and would not end.
inline constexpr double kMaxSteps = 1e10;

/// round(seconds / dt), at least 1; throws UsageError naming `what` beyond kMaxSteps.
std::uint64_t stepCount(double seconds, double dt, const std::string& what);

/// Loads SCENE as typed: a built-in's name, or a file (with a note on stderr when a file here
/// has a built-in's name).
Scene loadSceneArgument(const std::string& nameOrPath);

/// Loads the scene and applies the overrides; throws SceneError or UsageError on bad input
/// (a duration of more than kMaxSteps steps of dt included).
Scene loadSceneWithOverrides(const SceneOptions& options);

} // namespace pba::app
