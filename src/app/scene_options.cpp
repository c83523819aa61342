#include "scene_options.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "flag_values.hpp"

namespace pba::app {

std::string builtinSceneList()
{
    std::vector<std::string> names = builtinSceneNames();
    std::sort(names.begin(), names.end()); // by name, not by file name: blow-dryer before blow-dryer-flow
    std::size_t width = 0;
    for (const auto& name : names)
        width = std::max(width, name.size());
    std::string text = "Built-in scenes (SCENE may also be a path to a JSON scene file, see docs/scenes.md):";
    for (const auto& name : names)
        text += fmt::format("\n  {:<{}}  {}", name, width, builtinSceneSummary(name));
    return text;
}

void listScenesInHelp(CLI::App& command)
{
    // CLI11 prints this callback's text, a line break, then the footer string (the examples).
    command.footer([] { return builtinSceneList(); });
}

void addScenePositional(CLI::App& command, std::string& scene, const std::string& defaultScene)
{
    scene = defaultScene;
    command.add_option("SCENE", scene,
                       fmt::format("A built-in scene (listed below) or a JSON scene file (default {})", defaultScene))
        ->type_name("");
    listScenesInHelp(command);
}

void addSceneOptions(CLI::App& command, SceneOptions& options, const std::string& defaultScene)
{
    addScenePositional(command, options.scene, defaultScene);
    command.add_option("--dt", options.dt, "Fixed physics timestep in seconds (overrides the scene)")
        ->transform(decimalOnly())
        ->type_name("SECONDS");
    command.add_option("--duration", options.duration, "Simulated time in seconds (overrides the scene)")
        ->transform(decimalOnly())
        ->type_name("SECONDS");
    command.add_option("--integrator", options.integrator,
                       "For every moving body: forward-euler, semi-implicit-euler, velocity-verlet, rk4; "
                       "implicit-gyroscopic or splitting (semi-implicit Euler or velocity Verlet whose rigid "
                       "rotation takes the implicit gyroscopic step or the momentum-keeping splitting); "
                       "implicit-euler or xpbd (particles joined by springs: backward Euler, or the springs as "
                       "constraints in --substeps; a particle with no spring moves as by semi-implicit Euler)")
        ->type_name("NAME");
    command.add_option("--substeps", options.substeps, "xpbd's substeps a step (overrides the scene; default 10)")
        ->transform(decimalOnly())
        ->type_name("N");
    command.add_option("--collision", options.collision,
                       "Collision response: exact (time of impact), reflect (mirror back) or clamp (put back)")
        ->type_name("MODE");
}

Integrator integratorFlag(const std::string& name)
{
    const auto integrator = integratorFromName(name);
    if (!integrator)
        throw UsageError(
            fmt::format("--integrator: unknown integrator '{}' (expected {})", name, integratorNameList()));
    return *integrator;
}

std::uint64_t stepCount(double seconds, double dt, const std::string& what)
{
    const double steps = std::round(seconds / dt);
    if (!(steps <= kMaxSteps))
        throw UsageError(fmt::format("{}: {:g} s at dt = {:g} s is {:.3g} steps, more than the {:g} a run may take",
                                     what, seconds, dt, steps, kMaxSteps));
    return static_cast<std::uint64_t>(std::max(1.0, steps));
}

Scene loadSceneArgument(const std::string& nameOrPath)
{
    // A built-in's name wins over a file of that name in the current folder; say so, since the
    // user may have meant the file.
    std::error_code ec;
    if (!builtinSceneText(nameOrPath).empty() && std::filesystem::is_regular_file(nameOrPath, ec))
        fmt::print(stderr, "pba: note: '{0}' is the built-in scene; for the file of that name here, give ./{0}\n",
                   nameOrPath);
    return loadScene(nameOrPath);
}

Scene loadSceneWithOverrides(const SceneOptions& options)
{
    Scene scene = loadSceneArgument(options.scene);
    if (options.dt) {
        if (!std::isfinite(*options.dt) || *options.dt <= 0.0)
            throw UsageError(fmt::format("--dt: must be finite and positive, got {}", *options.dt));
        scene.dt = *options.dt;
    }
    if (options.duration) {
        if (!std::isfinite(*options.duration) || *options.duration <= 0.0)
            throw UsageError(fmt::format("--duration: must be finite and positive, got {}", *options.duration));
        scene.duration = *options.duration;
    }
    if (options.integrator) {
        const Integrator integrator = integratorFlag(*options.integrator);
        if (isSpringSystemMethod(integrator))
            for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
                if (scene.world.isRigid(i) && !scene.world.body(i).isFixed())
                    throw UsageError(fmt::format("--integrator: {} steps particles joined by springs, and {} has "
                                                 "rigid body '{}' (a rope's or cloth's own \"integrator\" key "
                                                 "sets it for that one)",
                                                 *options.integrator, scene.source, scene.world.body(i).getName()));
        if (isSpringSystemMethod(integrator) && scene.world.swarmCount() > 0)
            throw UsageError(fmt::format("--integrator: {} steps particles joined by springs, and {} has swarm "
                                         "'{}', which has none", *options.integrator, scene.source,
                                         scene.world.swarm(0).name()));
        for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
            if (!scene.world.body(i).isFixed())
                scene.world.body(i).setIntegrator(integrator);
        for (std::size_t i = 0; i < scene.world.swarmCount(); ++i)
            scene.world.swarm(i).setIntegrator(integrator);
    }
    if (options.substeps) {
        if (*options.substeps < 1 || *options.substeps > World::kMaxXpbdSubsteps)
            throw UsageError(fmt::format("--substeps: must be from 1 to {}, got {}", World::kMaxXpbdSubsteps,
                                         *options.substeps));
        scene.world.setXpbdSubsteps(*options.substeps);
    }
    if (options.collision) {
        const auto response = collisionResponseFromName(*options.collision);
        if (!response)
            throw UsageError(fmt::format("--collision: unknown collision response '{}' (expected {})",
                                         *options.collision, collisionResponseNameList()));
        scene.world.setCollisionResponse(*response);
    }
    stepCount(scene.duration, scene.dt,
              options.duration ? "--duration" : options.dt ? "--dt" : fmt::format("{}: duration", scene.source));
    return scene;
}

} // namespace pba::app
