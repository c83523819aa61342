// `pba scenes`: the built-in scenes, one line each, as every scene-taking command's --help lists them.
#include <fmt/format.h>

#include "command.hpp"
#include "scene_options.hpp"

namespace pba::app {

void addScenesCommand(CLI::App& root, Action& selected)
{
    CLI::App* scenes = root.add_subcommand("scenes", "List the built-in scenes, one line each");
    scenes->callback([&selected] {
        selected = [] {
            fmt::print("{}\n", builtinSceneList());
            return kExitSuccess;
        };
    });
}

} // namespace pba::app
