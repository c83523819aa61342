// `pba view`: the interactive window.
#include <cstdlib>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "command.hpp"
#include "scene_options.hpp"
#include "viewer.hpp"
#include "render/gl_context.hpp"

namespace pba::app {

namespace {

struct ViewOptions {
    SceneOptions scene;
    std::optional<int> frames;
    std::optional<std::string> screenshot;
    bool lanes = false;
};

int runView(const ViewOptions& options)
{
    Scene scene = loadSceneWithOverrides(options.scene);
    if (options.frames && *options.frames <= 0)
        throw UsageError(fmt::format("--frames: must be positive, got {}", *options.frames));
    if (options.screenshot && !options.frames)
        throw UsageError("--screenshot needs --frames N (the frame to save)");
    try {
        return runViewer(std::move(scene), options.frames, options.screenshot, options.lanes);
    } catch (const render::RenderError& e) {
        throw RuntimeFailure(e.what());
    }
}

} // namespace

int runDefault(const std::string& directory)
{
    const char* display = std::getenv("DISPLAY");
    if (display && *display) {
        try {
            return runViewer(loadScene(kDefaultScene), std::nullopt, std::nullopt);
        } catch (const render::RenderError& e) {
            fmt::print(stderr, "pba: no window ({}); rendering instead\n", e.what());
        }
    }
    return renderDefaultScene(directory);
}

void addViewCommand(CLI::App& root, Action& selected)
{
    auto options = std::make_shared<ViewOptions>();
    CLI::App* view = root.add_subcommand("view", "Open the interactive viewer (needs a display; see `pba render` "
                                                 "for none)");
    addSceneOptions(*view, options->scene, kDefaultScene);
    view->add_option("--frames", options->frames, "Run this many frames, then close")->type_name("N");
    view->add_option("--screenshot", options->screenshot, "With --frames: save the last frame to this PNG")
        ->type_name("FILE.png");
    view->add_flag("--lanes", options->lanes, "Integrator lanes: the exact solution's ghost beside each particle");
    view->footer("\nKeys: space pause/play, '.' or right arrow single step, r reset, i toggle interpolation,\n"
                 "      c reset the camera, Esc quit.\n"
                 "Mouse: drag to orbit, right-drag or shift-drag to pan, wheel to zoom.\n"
                 "Without a display: `pba render SCENE --out pba-out/shot.png --time T` draws the same picture;\n"
                 "under xvfb-run the window is invisible and runs until --frames N (or --time T) ends it.\n");
    view->callback([options, &selected] { selected = [options] { return runView(*options); }; });
}

} // namespace pba::app
