// `pba render`: the viewer's pictures without a display: one PNG, numbered PNG frames, or an
// MP4. Video time follows the fixed-timestep clock fed with frames of 1/fps seconds, so the
// interpolation between physics states is exercised exactly as in the window.
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <regex>

#include <fmt/format.h>

#include "command.hpp"
#include "flag_values.hpp"
#include "frame_steps.hpp"
#include "lanes.hpp"
#include "picture_options.hpp"
#include "progress.hpp"
#include "io/output_file.hpp"
#include "render_output.hpp"
#include "scene_options.hpp"
#include "shown_path.hpp"
#include "pba/clock.hpp"
#include "render/image_io.hpp"
#include "render/offscreen.hpp"

namespace pba::app {

namespace {

struct RenderOptions {
    SceneOptions scene;
    std::string out;
    std::optional<double> time;
    int fps = 60;
    std::string size = "1280x720";
    bool arrows = false;
    bool noTrails = false;
    bool noLegend = false;
    bool lanes = false;
    std::optional<std::string> camera;
    std::optional<std::string> show;
    std::string clock = "fixed";
    bool noInterpolation = false;
};

/// A picture's pixels: rendering one takes about 45 bytes a pixel at its peak (multisampled colour
/// and depth, the resolved and read-back copies, the PNG's rows), so 8192x8192 took 3 GB.
constexpr double kMaxPixels = 4096.0 * 4096.0;
constexpr double kRenderBytesPerPixel = 45.0;

void parseSize(const std::string& text, int& width, int& height)
{
    static const std::regex pattern(R"((\d{1,5})x(\d{1,5}))");
    std::smatch m;
    if (!std::regex_match(text, m, pattern) || (width = std::stoi(m[1])) < 16 || (height = std::stoi(m[2])) < 16 ||
        width > 8192 || height > 8192)
        throw UsageError(fmt::format("--size: expected WxH between 16 and 8192, e.g. 1280x720, got '{}'", text));
    if (const double pixels = double(width) * height; pixels > kMaxPixels)
        throw UsageError(fmt::format("--size: {} is {:.1f} million pixels, more than the {:.1f} million (4096x4096) "
                                     "a picture may have: it would take about {:.1f} GB to render",
                                     text, pixels / 1e6, kMaxPixels / 1e6, pixels * kRenderBytesPerPixel / 1e9));
}

int runRender(const RenderOptions& options)
{
    Scene scene = loadSceneWithOverrides(options.scene);
    int width = 0, height = 0;
    parseSize(options.size, width, height);
    if (options.fps <= 0 || options.fps > 1000)
        throw UsageError(fmt::format("--fps: must be between 1 and 1000, got {}", options.fps));
    const ClockKind clock = parseClockOption(options.clock);
    const OutputKind kind = outputKind(options.out);
    if (options.time && kind != OutputKind::Png)
        throw UsageError("--time applies to a single PNG (--out FILE.png)");
    const double until = options.time.value_or(scene.duration);
    if (!std::isfinite(until) || until < 0.0)
        throw UsageError(fmt::format("--time: must be finite and not negative, got {}", until));
    // A user who gives both means the picture to lie within the run: a later --time is a slip.
    if (options.time && options.scene.duration && *options.time > *options.scene.duration)
        throw UsageError(fmt::format("--time: {:g} s is past --duration {:g} s", *options.time, *options.scene.duration));
    stepCount(until, scene.dt, options.time ? "--time" : "--duration");
    if (!(until * options.fps <= kMaxSteps))
        throw UsageError(fmt::format("--duration: {:g} s at {} frames a second is more than {:g} frames", until,
                                     options.fps, kMaxSteps));
    render::ViewSettings settings;
    const std::optional<CameraChoice> camera =
        options.camera ? std::optional(parseCamera(*options.camera)) : std::nullopt;
    if (options.show)
        applyShow(*options.show, settings);
    FrameSink sink(kind, options.out, width, height, options.fps); // checks the path before any work

    settings.fieldArrows = options.arrows;
    settings.interpolate = !options.noInterpolation;
    settings.trails = !options.noTrails;
    settings.fabric = scene.fabric;
    settings.dice = scene.dice;
    if (options.lanes)
        settings.ghost = exactGhosts(scene.world);
    render::OffscreenRenderer renderer(width, height, !options.noLegend);
    renderer.setCamera(cameraFor(camera, scene.world, scene.camera), framingCamera(camera, scene.camera));
    render::Trails trails;
    const World initial = scene.world;
    const auto frames = static_cast<long>(std::floor(until * options.fps + 1e-9)) + 1;
    Progress progress("rendering", frames);
    double alpha = 0.0;
    double shownTime = 0.0; // the last frame's time: the semi-fixed and variable clocks step the frame between
    BlowUpWatch watch(scene.world);
    try {
        for (long frame = 0; frame < frames; ++frame) {
            // A PNG's last frame is at exactly --time, not at the last frame of 1/fps before it
            // (the frames before it only feed the trails).
            const bool last = frame == frames - 1;
            const double t = kind == OutputKind::Png && last ? until : double(frame) / options.fps;
            alpha = clock == ClockKind::Fixed ? stepToFrame(scene, t, watch)
                                              : stepFrameWith(clock, scene, t - shownTime, watch);
            shownTime = t;
            trails.record(scene.world, alpha, settings);
            if (kind != OutputKind::Png || last)
                sink.add(renderer.render(scene.world, initial, alpha, settings, &trails, scene.name, scene.dt));
            progress.update(frame + 1);
        }
    } catch (const BlowUpError& error) {
        fmt::print(stderr, "pba: error: {}: {}\n", shownPath(scene.source), error.what());
        return kExitSimulationFailure;
    }
    sink.finish();
    // H.264's colour planes need even sizes: the video is padded by a row or a column of black.
    const bool padded = kind == OutputKind::Mp4 && (width % 2 != 0 || height % 2 != 0);
    const std::string size = padded ? fmt::format("{}x{}, padded from {}x{} as H.264 needs even sizes",
                                                  width + width % 2, height + height % 2, width, height)
                                    : fmt::format("{}x{}", width, height);
    progress.finish(fmt::format("wrote {} ({} frame{}, {}, t = {:.3g} s)", shownPath(options.out),
                                kind == OutputKind::Png ? 1 : frames, kind == OutputKind::Png || frames == 1 ? "" : "s",
                                size, render::drawnTime(scene.world, alpha, settings.interpolate)));
    if (renderer.legendCovers() > render::OffscreenRenderer::kMostLegend) {
        std::fflush(stdout); // after the "wrote" line
        fmt::print(stderr, "pba: note: the legend was left out: it would have covered {:.0f}% of the {}x{} picture's "
                           "height (from about 640x360 it fits)\n", 100.0f * renderer.legendCovers(), width, height);
    }
    return kExitSuccess;
}

} // namespace

int renderDefaultScene(const std::string& directory)
{
    // The user typed no --out: a folder that cannot be made or written is named as what it is.
    std::error_code ec;
    std::filesystem::create_directories(directory, ec);
    if (ec || ::access(directory.c_str(), W_OK) != 0)
        throw io::BadOutput(fmt::format("{}: cannot be {} ({}): pba without a command renders into it, so run it "
                                        "from a folder you may write in",
                                        directory, ec ? "made" : "written", ec ? ec.message() : std::strerror(errno)));
    // Twenty seconds of silence look like a hang: say what is coming before the work starts.
    fmt::print(stderr, "pba: no display: rendering the {} scene to {}/{}.mp4 and {}/{}.png (about 20 s)...\n",
               kDefaultScene, directory, kDefaultScene, directory, kDefaultScene);
    RenderOptions options;
    options.scene.scene = kDefaultScene;
    options.scene.duration = 10.0;
    const std::string video = directory + "/" + kDefaultScene + ".mp4", still = directory + "/" + kDefaultScene + ".png";
    // Both paths are checked before the video's 20 s: a user's still there refused after them left
    // the video written and the run refused.
    io::resolveOutputFile(still);
    options.out = video;
    if (const int code = runRender(options); code != kExitSuccess)
        return code;
    options.out = still;
    options.time = 10.0;
    if (const int code = runRender(options); code != kExitSuccess)
        return code;
    fmt::print("no display: rendered the {0} scene instead of opening a window:\n  {1}/{0}.mp4\n  {1}/{0}.png\n"
               "Other scenes and moments: `pba render SCENE --out {1}/SCENE.png --time T` (or .mp4), or\n"
               "`pba view SCENE --time T --screenshot {1}/shot.png` under xvfb-run (`pba scenes` lists them).\n",
               kDefaultScene, directory);
    return kExitSuccess;
}

void addRenderCommand(CLI::App& root, Action& selected)
{
    auto options = std::make_shared<RenderOptions>();
    CLI::App* render = root.add_subcommand("render", "Render a scene headless (no display needed) to a PNG, "
                                                     "numbered PNG frames, or an MP4 video");
    addSceneOptions(*render, options->scene, kDefaultScene);
    render->add_option("--out", options->out, "FILE.png (one frame), FILE.mp4 (H.264 video) or DIR/ (numbered PNGs)")
        ->required()
        ->type_name("PATH");
    render->add_option("--time", options->time, "With a PNG: the simulated time to show (default: the end)")
        ->transform(decimalOnly())
        ->type_name("SECONDS");
    render->add_option("--fps", options->fps, "Frames per second of video time (default 60); with a PNG, the frames "
                                             "that feed its trails and a --clock other than fixed")
        ->transform(decimalOnly())
        ->type_name("HZ");
    render->add_option("--size", options->size, "Image size, 16 to 8192 a side and at most 4096x4096 pixels in all "
                                               "(default 1280x720)")->type_name("WxH");
    render->add_option("--clock", options->clock, kClockOptionHelp)->type_name("NAME");
    render->add_flag("--no-interpolation", options->noInterpolation,
                     "Draw the last physics state made rather than the state interpolated to the frame's time (the "
                     "stutter the fixed clock's interpolation hides)");
    render->add_flag("--arrows", options->arrows, "Draw the blow dryer's field as arrows inside its cone");
    render->add_flag("--no-trails", options->noTrails, "Do not draw the particles' fading trails");
    render->add_flag("--no-legend", options->noLegend,
                     "Do not draw the legend (the scene, the time, the collision rules and each body's colour) in "
                     "the lower left");
    render->add_flag("--lanes", options->lanes, "Integrator lanes: a ghost of the exact solution beside each particle "
                                                "that has one (the integrators and spring scenes)");
    addPictureFlags(*render, options->camera, options->show);
    render->footer("\nExamples:\n  pba render integrators --out pba-out/integrators.png --time 1.2\n"
                   "  pba render blow-dryer --out pba-out/blow-dryer.mp4 --duration 10\n"
                   "  pba render spring --out pba-out/frames/ --fps 30\n"
                   "  pba render dominoes --camera -0.6,1.3,2.8,-1,0.1,0 --show contacts --time 1.6 --out pba-out/d.png\n"
                   "  pba render pendulum --camera 0,2.5,5,0,2,0 --show joints,axes --out pba-out/pendulum.png\n");
    render->callback([options, &selected] { selected = [options] { return runRender(*options); }; });
}

} // namespace pba::app
