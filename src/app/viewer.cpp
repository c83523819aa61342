#include "viewer.hpp"

#include <algorithm>
#include <chrono>

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>

#include "atomic_file.hpp"
#include "command.hpp"
#include "shown_path.hpp"
#include "io/output_file.hpp"
#include "key_input.hpp"
#include "lanes.hpp"
#include "render/gl_context.hpp"
#include "render/image_io.hpp"
#include "render/overlay.hpp"
#include "render/renderer.hpp"
#include "render/world_view.hpp"

namespace pba::app {

namespace {

/// Orbit with the left mouse button, pan with the right one (or shift-drag), zoom with the wheel.
void handleMouse(render::OrbitCamera& camera)
{
    const ImGuiIO& io = ImGui::GetIO();
    if (io.WantCaptureMouse)
        return;
    const bool pan = ImGui::IsMouseDown(ImGuiMouseButton_Right) || (ImGui::IsMouseDown(ImGuiMouseButton_Left) && io.KeyShift);
    if (pan)
        camera.pan(-io.MouseDelta.x * 0.0015f, io.MouseDelta.y * 0.0015f);
    else if (ImGui::IsMouseDown(ImGuiMouseButton_Left))
        camera.orbit(-io.MouseDelta.x * 0.006f, io.MouseDelta.y * 0.006f);
    if (io.MouseWheel != 0.0f)
        camera.zoom(io.MouseWheel > 0 ? 0.9f : 1.0f / 0.9f);
}

/// GLFW calls this for every key event, whatever the frame rate; the frame takes the queue.
void onKey(GLFWwindow* window, int key, int /*scancode*/, int action, int mods)
{
    static_cast<KeyInput*>(glfwGetWindowUserPointer(window))->onKey(key, action, mods);
}

/// The keys queued since the last frame, in order. Typing in a text box is not a command.
void applyKeys(ViewerState& state, KeyInput& keys)
{
    const std::vector<ViewerCommand> commands = keys.take();
    if (ImGui::GetIO().WantCaptureKeyboard)
        return;
    for (const ViewerCommand command : commands)
        state.apply(command);
}

/// Where a frame of the capture (`--time T`) is.
enum class CaptureFrame { Before, AtTime, Last };

/// The capture's synthetic frame k shows t = k / kCaptureFps, the last ones exactly T: a few
/// frames at T let ImGui's self-sizing windows settle before the picture is taken.
CaptureFrame captureFrame(ViewerState& state, int frame, double until)
{
    const double t = std::min(double(frame) / kCaptureFps, until);
    state.advanceTo(t);
    return t < until ? CaptureFrame::Before : frame >= 2 ? CaptureFrame::Last : CaptureFrame::AtTime;
}

/// Seconds since the last frame, smoothed into the panel's frame rate. A capture's frames are
/// 1 / kCaptureFps apart, whatever the real time.
double frameSeconds(ViewerState& state, std::chrono::steady_clock::time_point& last, bool capturing)
{
    const auto now = std::chrono::steady_clock::now();
    const double measured = std::chrono::duration<double>(now - last).count();
    last = now;
    if (capturing) {
        state.frameRate = float(kCaptureFps);
        return 1.0 / kCaptureFps;
    }
    if (measured > 0.0)
        state.frameRate = 0.9f * state.frameRate + 0.1f * float(1.0 / measured);
    return measured;
}

/// The frame's trails, legend and panel and, when `drawScene`, the scene beside the panel.
/// Returns the framebuffer's size.
glm::ivec2 drawFrame(ViewerState& state, render::WindowContext& window, render::Renderer& renderer,
                     render::DrawList& list, bool drawScene)
{
    state.trails.record(state.scene.world, state.alpha(), state.settings);
    const float display = ImGui::GetIO().DisplaySize.x;
    const glm::vec2 legend = render::drawLegend(
        state.scene.world, state.scene.name, state.clock.dt(),
        render::drawnTime(state.scene.world, state.alpha(), state.settings.interpolate), true,
        &state.settings.fabric, display - state.panelWidth);
    const float panel = drawPanel(state);
    state.panelWidth = panel;
    int width = 0, height = 0;
    window.framebufferSize(width, height);
    // ImGui's auto-sized window reports a stand-in size on its first frame: the legend's is
    // taken once it is the same two frames running.
    const bool settled = legend == state.lastLegend && legend.y > 0.0f;
    state.lastLegend = legend;
    if (state.clearLegend && settled) {
        state.camera = render::clearOfLegend(state.camera, state.initial, std::max(width - int(panel), 1),
                                             std::max(height, 1), legend);
        state.clearLegend = false;
    }
    window.bindForDrawing();
    if (drawScene) {
        render::buildDrawList(state.scene.world, state.initial, state.alpha(), state.settings, &state.trails, list);
        renderer.draw(list, state.camera, std::max(width - int(panel), 1), std::max(height, 1));
    }
    return {width, height};
}

/// `--screenshot`'s picture of the frame just drawn, and the exit code: a failure when the
/// simulation stopped on a bad state before T.
int saveScreenshot(const ViewerState& state, render::WindowContext& window, glm::ivec2 size,
                   const std::filesystem::path& shot, const ViewerRun& run)
{
    render::writePng(shot, size.x, size.y, window.readPixels());
    // The state drawn: T itself, or without interpolation the last one the steps made (2.01 s
    // for T = 2.005 at dt 0.01), as the picture's legend says.
    fmt::print("wrote {} (t = {:g} s)\n", shownPath(*run.screenshot),
               render::drawnTime(state.scene.world, state.alpha(), state.settings.interpolate));
    if (state.error)
        fmt::print(stderr, "pba: error: {}: {}\n", shownPath(state.scene.source), *state.error);
    return state.error ? kExitSimulationFailure : kExitSuccess;
}

} // namespace

int runViewer(Scene scene, const ViewerRun& run)
{
    const std::optional<std::filesystem::path> shot =
        run.screenshot ? std::optional(resolveWritableFile("--screenshot", *run.screenshot)) : std::nullopt; // before the window opens
    KeyInput keys; // outlives the window, whose key callback writes to it
    render::WindowContext window(1280, 720, fmt::format("pba: {}", scene.name));
    glfwSetWindowUserPointer(window.window(), &keys);
    glfwSetKeyCallback(window.window(), onKey); // before ImGui's backend, which calls it on
    render::Renderer renderer;
    render::ImGuiLayer imgui(window.window());
    ViewerState state;
    state.pauseAt = run.pauseAt;
    state.clockKind = run.clock;
    if (run.noInterpolation)
        state.settings.interpolate = false;
    state.cameraChoice = run.camera;
    if (run.show)
        applyShow(*run.show, state.settings);
    if (run.lanes)
        state.settings.ghost = [](std::size_t, double) { return std::optional<glm::vec3>(); }; // set by load()
    state.load(std::move(scene));
    render::DrawList list;
    bool capturing = run.time.has_value(); // synthetic frames to run.time: no real time, no input
    const double captureUntil = run.time.value_or(0.0);
    auto last = std::chrono::steady_clock::now();
    for (int frame = 0; !window.shouldClose() && !state.quit && (!run.frames || frame < *run.frames); ++frame) {
        glfwPollEvents();
        const double seconds = frameSeconds(state, last, capturing);
        const CaptureFrame at = capturing ? captureFrame(state, frame, captureUntil) : CaptureFrame::AtTime;
        const bool captured = capturing && at == CaptureFrame::Last;
        imgui.beginFrame(0, 0, float(seconds));
        if (!capturing) {
            handleMouse(state.camera);
            applyKeys(state, keys);
            state.advance(seconds);
        } else {
            keys.take(); // keys pressed during a capture do not change it
        }
        // A capture's frames before T are not shown, so not drawn (a million particles are slow).
        const glm::ivec2 size = drawFrame(state, window, renderer, list, at != CaptureFrame::Before);
        imgui.endFrame();
        if (captured && shot)
            return saveScreenshot(state, window, size, *shot, run);
        if (captured) { // the window stays open, paused at the time asked for
            capturing = false;
            state.paused = true;
        }
        if (at != CaptureFrame::Before)
            window.swap();
    }
    return kExitSuccess;
}

} // namespace pba::app
