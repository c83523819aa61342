#pragma once
// The options that override a scene, shared by every subcommand that runs one.
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
};

/// Adds the positional SCENE (with `defaultScene`) and --dt, --duration, --integrator, --collision.
void addSceneOptions(CLI::App& command, SceneOptions& options, const std::string& defaultScene);

/// Loads the scene and applies the overrides; throws SceneError or UsageError on bad input.
Scene loadSceneWithOverrides(const SceneOptions& options);

} // namespace pba::app
