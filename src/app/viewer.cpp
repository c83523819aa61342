#include "viewer.hpp"

#include <algorithm>
#include <chrono>

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>

#include "command.hpp"
#include "io/output_file.hpp"
#include "lanes.hpp"
#include "render/gl_context.hpp"
#include "render/image_io.hpp"
#include "render/overlay.hpp"
#include "render/renderer.hpp"

namespace pba::app {

void History::push(std::size_t body, float value)
{
    auto& v = m_values[body];
    if (v.size() == kLength)
        v.erase(v.begin());
    v.push_back(value);
}

void History::clear()
{
    for (auto& v : m_values)
        v.clear();
}

void ViewerState::load(Scene newScene)
{
    scene = std::move(newScene);
    scene.world.setSwarmRollback(true); // a failed step pauses on the last finite state, swarms too
    scenePath = scene.source;
    camera = render::frameWorld(scene.world);
    initial = scene.world;
    if (settings.ghost)
        settings.ghost = exactGhosts(initial);
    clock = FixedTimestepClock(scene.dt, clock.maxFrameTime(), clock.maxStepsPerFrame());
    reset();
}

void ViewerState::reset()
{
    scene.world = initial;
    clock.reset();
    trails.clear();
    heights.resize(scene.world.bodyCount());
    energies.resize(scene.world.bodyCount());
    error.reset();
    record();
}

void ViewerState::advance(double frameSeconds)
{
    stepsThisFrame = 0;
    if (error)
        return;
    if (!paused && frameSeconds > 0.0)
        stepWorld(clock.advance(frameSeconds * timeScale));
    if (stepOnce) {
        stepWorld(1);
        stepOnce = false;
    }
}

void ViewerState::stepWorld(int steps)
{
    try {
        for (int n = 0; n < steps; ++n) {
            scene.world.step(clock.dt()); // the fixed dt: the frame time only decided how many steps
            ++stepsThisFrame;
            record();
        }
    } catch (const NonFiniteStateError& e) {
        error = e.what();
        paused = true;
    }
}

void ViewerState::record()
{
    const World& world = scene.world;
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        heights.push(i, float(world.body(i).getPos().y));
        const double e0 = initial.energy(i);
        energies.push(i, float(e0 != 0.0 ? world.energy(i) / e0 : 1.0));
    }
}

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

/// Space pause, '.' or right arrow single step, r reset, i interpolation, c camera, Esc quit.
void handleKeys(ViewerState& state, GLFWwindow* window)
{
    if (ImGui::GetIO().WantCaptureKeyboard)
        return;
    if (ImGui::IsKeyPressed(GLFW_KEY_SPACE))
        state.paused = !state.paused;
    if (ImGui::IsKeyPressed(GLFW_KEY_PERIOD) || ImGui::IsKeyPressed(GLFW_KEY_RIGHT)) {
        state.paused = true;
        state.stepOnce = true;
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_R, false))
        state.reset();
    if (ImGui::IsKeyPressed(GLFW_KEY_I, false))
        state.settings.interpolate = !state.settings.interpolate;
    if (ImGui::IsKeyPressed(GLFW_KEY_C, false))
        state.camera = render::frameWorld(state.initial);
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false))
        glfwSetWindowShouldClose(window, GLFW_TRUE);
}

} // namespace

int runViewer(Scene scene, std::optional<int> frames, std::optional<std::string> screenshot, bool lanes)
{
    const std::optional<std::filesystem::path> shot =
        screenshot ? std::optional(io::resolveOutputFile(*screenshot)) : std::nullopt; // before the window opens
    render::WindowContext window(1280, 720, fmt::format("pba: {}", scene.name));
    render::Renderer renderer;
    render::ImGuiLayer imgui(window.window());
    ViewerState state;
    if (lanes)
        state.settings.ghost = [](std::size_t, double) { return std::optional<glm::vec3>(); }; // set by load()
    state.load(std::move(scene));
    render::DrawList list;
    auto last = std::chrono::steady_clock::now();
    for (int frame = 0; !window.shouldClose() && (!frames || frame < *frames); ++frame) {
        glfwPollEvents();
        const auto now = std::chrono::steady_clock::now();
        const double seconds = std::chrono::duration<double>(now - last).count();
        last = now;
        state.frameRate = seconds > 0.0 ? 0.9f * state.frameRate + 0.1f * float(1.0 / seconds) : state.frameRate;

        imgui.beginFrame(0, 0, float(seconds));
        handleMouse(state.camera);
        handleKeys(state, window.window());
        state.advance(seconds);
        state.trails.record(state.scene.world, state.clock.alpha(), state.settings.interpolate);
        render::drawLegend(state.scene.world, state.scene.name, state.clock.dt(),
                           render::drawnTime(state.scene.world, state.clock.alpha(), state.settings.interpolate), true);
        drawPanel(state);

        int width = 0, height = 0;
        window.framebufferSize(width, height);
        render::buildDrawList(state.scene.world, state.initial, state.clock.alpha(), state.settings, &state.trails, list);
        window.bindForDrawing();
        renderer.draw(list, state.camera, width, std::max(height, 1));
        imgui.endFrame();
        if (screenshot && frames && frame == *frames - 1)
            render::writePng(*shot, width, height, window.readPixels());
        window.swap();
    }
    if (screenshot)
        fmt::print("wrote {}\n", *screenshot);
    return kExitSuccess;
}

} // namespace pba::app
