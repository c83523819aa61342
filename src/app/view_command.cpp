// `pba view`: the interactive window.
#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "command.hpp"
#include "flag_values.hpp"
#include "render_output.hpp"
#include "scene_options.hpp"
#include "picture_options.hpp"
#include "frame_steps.hpp"
#include "viewer.hpp"
#include "render/gl_context.hpp"

namespace pba::app {

namespace {

struct ViewOptions {
    SceneOptions scene;
    std::optional<int> frames;
    std::optional<double> time;
    std::optional<std::string> screenshot;
    bool lanes = false;
    std::optional<std::string> camera;
    std::optional<std::string> show;
    std::string clock = "fixed";
    bool noInterpolation = false;
};

int runView(const ViewOptions& options)
{
    Scene scene = loadSceneWithOverrides(options.scene);
    if (options.frames && *options.frames <= 0)
        throw UsageError(fmt::format("--frames: must be positive, got {}", *options.frames));
    if (options.screenshot && !options.time)
        throw UsageError("--screenshot needs --time T (the simulated time to save)");
    // It is saved as a PNG: another name (shot.jpg) would hold a PNG under a JPEG's name.
    if (options.screenshot && lowerExtension(*options.screenshot) != ".png")
        throw UsageError(fmt::format("--screenshot: expected FILE.png, got '{}'", *options.screenshot));
    if (options.time && options.frames)
        throw UsageError("--time and --frames: choose one");
    if (options.time) {
        if (!std::isfinite(*options.time) || *options.time < 0.0)
            throw UsageError(fmt::format("--time: must be finite and not negative, got {}", *options.time));
        stepCount(*options.time, scene.dt, "--time");
        if (*options.time * kCaptureFps > 1e9) // the capture's frames are counted in an int
            throw UsageError(fmt::format("--time: {:g} s is more than 1e9 frames of 1/{} s", *options.time, kCaptureFps));
        if (options.scene.duration && *options.time > *options.scene.duration)
            throw UsageError(fmt::format("--time: {:g} s is past --duration {:g} s", *options.time, *options.scene.duration));
    }
    ViewerRun run;
    run.frames = options.frames;
    run.time = options.time;
    run.screenshot = options.screenshot;
    run.pauseAt = options.scene.duration; // only when asked for: a scene's duration sizes batch runs
    run.lanes = options.lanes;
    run.clock = parseClockOption(options.clock);
    run.noInterpolation = options.noInterpolation;
    if (options.camera)
        run.camera = parseCamera(*options.camera);
    if (options.show) {
        render::ViewSettings checked;
        applyShow(*options.show, checked); // refused here, before the window opens
        run.show = options.show;
    }
    try {
        return runViewer(std::move(scene), run);
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
            return runViewer(loadScene(kDefaultScene), ViewerRun{});
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
    view->get_option("--duration")->description("Pause when the simulated time reaches this (seconds)");
    view->add_option("--frames", options->frames,
                     "Run this many frames of real time, then close (the simulated time reached depends on "
                     "the machine)")
        ->transform(decimalOnly())
        ->type_name("N");
    view->add_option("--time", options->time,
                     "Run to exactly this simulated time with synthetic frames of 1/60 s (as pba render), then "
                     "stay paused there, or with --screenshot save it and close")
        ->transform(decimalOnly())
        ->type_name("SECONDS");
    view->add_option("--screenshot", options->screenshot, "With --time: save the window at that time to this PNG")
        ->type_name("FILE.png");
    view->add_option("--clock", options->clock, kClockOptionHelp)->type_name("NAME");
    view->add_flag("--no-interpolation", options->noInterpolation,
                   "Draw the last physics state made rather than the one interpolated to the frame (key i toggles it)");
    view->add_flag("--lanes", options->lanes, "Integrator lanes: the exact solution's ghost beside each particle");
    addPictureFlags(*view, options->camera, options->show);
    view->footer("\n--duration D pauses the run when the simulated time reaches D (play goes on past it).\n"
                 "Keys: space pause/play, '.' or right arrow single step, r reset (restart with the panel's\n"
                 "      settings), R (shift+r) reload the scene's own settings, i toggle interpolation,\n"
                 "      c the start's camera again, n contact points and normals, j joint frames,\n"
                 "      a rigid bodies' axes with omega and L, Esc quit.\n"
                 "Mouse: drag to orbit, right-drag or shift-drag to pan, wheel to zoom.\n"
                 "Without a display: `pba render SCENE --out pba-out/frame.png --time T` draws the scene, or\n"
                 "xvfb-run -a -s \"-screen 0 1280x720x24\" pba view SCENE --time T --screenshot pba-out/shot.png\n"
                 "captures the window with its panel (the invisible window closes after the shot).\n"
                 "\nExamples:\n  pba view integrators --lanes\n"
                 "  pba view tennis-racket --camera 1.4,2.6,2.2,0,2,0 --show axes\n"
                 "  pba view dominoes --show contacts --time 1.5 --screenshot pba-out/dominoes.png\n");
    view->callback([options, &selected] { selected = [options] { return runView(*options); }; });
}

} // namespace pba::app
