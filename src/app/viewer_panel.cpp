// The viewer's control panel. Every control changes the scene or the view through the same
// calls a program would use; nothing here touches frame time.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <imgui.h>

#include "pba/blow_dryer.hpp"
#include "lanes.hpp"
#include "viewer.hpp"

namespace pba::app {

namespace {

constexpr const char* kIntegratorNames[] = {"forward-euler", "semi-implicit-euler", "velocity-verlet", "rk4"};
constexpr const char* kFalloffNames[] = {"linear", "quadratic", "smooth"};
constexpr const char* kDirectionNames[] = {"vertical", "cone-flow"};
constexpr const char* kResponseNames[] = {"exact", "reflect", "clamp"}; // in CollisionResponse's order

void sceneSection(ViewerState& state)
{
    static const std::vector<std::string> names = builtinSceneNames();
    if (ImGui::BeginCombo("scene", state.scene.name.c_str())) {
        for (const auto& name : names)
            if (ImGui::Selectable(name.c_str(), name == state.scene.name))
                state.load(loadScene(name));
        ImGui::EndCombo();
    }
    static char path[512] = "";
    ImGui::InputTextWithHint("##path", "path/to/scene.json", path, sizeof path);
    ImGui::SameLine();
    if (ImGui::Button("load")) {
        try {
            state.load(loadScene(path));
        } catch (const std::exception& e) {
            state.error = e.what();
        }
    }
}

/// The collision response, applied live and kept by reset (the start state gets it too), so the
/// practical's reflect and the exact response can be compared on the same drop.
void collisionChoice(ViewerState& state)
{
    if (state.scene.world.planes().empty())
        return;
    int response = static_cast<int>(state.scene.world.collisionResponse());
    if (ImGui::Combo("collision response", &response, kResponseNames, 3)) {
        state.scene.world.setCollisionResponse(static_cast<CollisionResponse>(response));
        state.initial.setCollisionResponse(static_cast<CollisionResponse>(response));
    }
}

void timeSection(ViewerState& state)
{
    if (ImGui::Button(state.paused ? "play (space)" : "pause (space)"))
        state.paused = !state.paused;
    ImGui::SameLine();
    if (ImGui::Button("step (.)")) {
        state.paused = true;
        state.stepOnce = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("reset (r)"))
        state.reset();
    float dt = float(state.clock.dt());
    if (ImGui::SliderFloat("dt (s)", &dt, 0.0005f, 0.1f, "%.4f", ImGuiSliderFlags_Logarithmic)) {
        state.clock.setDt(dt);
        state.scene.dt = dt;
    }
    ImGui::SliderFloat("time scale", &state.timeScale, 0.05f, 2.0f, "%.2fx", ImGuiSliderFlags_Logarithmic);
    collisionChoice(state);
    ImGui::Checkbox("interpolate (i)", &state.settings.interpolate);
    float clamp = float(state.clock.maxFrameTime());
    if (ImGui::SliderFloat("frame clamp (s)", &clamp, 0.02f, 1.0f, "%.2f"))
        state.clock.setMaxFrameTime(clamp);
    int cap = state.clock.maxStepsPerFrame();
    if (ImGui::SliderInt("steps cap", &cap, 1, 2000))
        state.clock.setMaxStepsPerFrame(cap);
    ImGui::Text("%.0f fps   %d steps this frame   alpha %.2f   t = %.3f s", state.frameRate, state.stepsThisFrame,
                state.clock.alpha(), state.scene.world.time());
}

void viewSection(ViewerState& state)
{
    ImGui::Checkbox("trails", &state.settings.trails);
    ImGui::SameLine();
    ImGui::Checkbox("start heights", &state.settings.referenceLines);
    ImGui::SameLine();
    ImGui::Checkbox("cone", &state.settings.cone);
    ImGui::SameLine();
    ImGui::Checkbox("arrows", &state.settings.fieldArrows);
    bool lanes = static_cast<bool>(state.settings.ghost);
    if (ImGui::Checkbox("lanes (exact ghost)", &lanes))
        state.settings.ghost = lanes ? exactGhosts(state.initial) : nullptr;
}

void particlesSection(ViewerState& state)
{
    World& world = state.scene.world;
    const std::size_t shown = std::min<std::size_t>(world.bodyCount(), 12);
    for (std::size_t i = 0; i < shown; ++i) {
        Body& body = world.body(i);
        ImGui::PushID(static_cast<int>(i));
        const glm::vec4 c = render::bodyColour(body);
        ImGui::TextColored(ImVec4(c.r, c.g, c.b, 1), "%s", body.getName().c_str());
        const double e0 = state.initial.energy(i);
        ImGui::SameLine();
        ImGui::Text("  y = %.3f m   E/E0 = %.4f", body.getPos().y, e0 != 0.0 ? world.energy(i) / e0 : 1.0);
        if (!body.isFixed()) {
            int integrator = static_cast<int>(body.getIntegrator());
            ImGui::SetNextItemWidth(170);
            if (ImGui::Combo("integrator", &integrator, kIntegratorNames, 4))
                body.setIntegrator(static_cast<Integrator>(integrator));
            ImGui::SameLine();
            float e = float(body.getCor());
            ImGui::SetNextItemWidth(100);
            if (ImGui::SliderFloat("e", &e, 0.0f, 1.0f, "%.2f"))
                body.setCor(e);
        }
        ImGui::PopID();
    }
}

void plotsSection(const ViewerState& state)
{
    const std::size_t shown = std::min<std::size_t>(state.heights.bodies(), 6);
    for (std::size_t i = 0; i < shown; ++i) {
        const auto& h = state.heights.values(i);
        const auto& e = state.energies.values(i);
        const std::string& name = state.scene.world.body(i).getName();
        ImGui::PlotLines(fmt::format("height {}", name).c_str(), h.data(), static_cast<int>(h.size()), 0, nullptr,
                         FLT_MAX, FLT_MAX, ImVec2(0, 40));
        ImGui::PlotLines(fmt::format("E/E0 {}", name).c_str(), e.data(), static_cast<int>(e.size()), 0, nullptr,
                         FLT_MAX, FLT_MAX, ImVec2(0, 40));
    }
}

/// The hole in the floor follows the nozzle (it is the nozzle's opening).
void moveHole(World& world, const BlowDryerField& f)
{
    const auto& hole = world.floorHole();
    if (hole && f.nozzleRadius > 0.0)
        world.setFloorHole(FloorHole{f.nozzle, f.nozzleRadius, hole->depth});
}

void dryerSection(ViewerState& state)
{
    World& world = state.scene.world;
    for (std::size_t i = 0; i < world.forceCount(); ++i) {
        auto* dryer = dynamic_cast<BlowDryer*>(&world.force(i));
        if (!dryer)
            continue;
        BlowDryerField& f = dryer->field();
        ImGui::PushID(static_cast<int>(i));
        float strength = float(f.strength), height = float(f.height), r0 = float(f.nozzleRadius),
              top = float(f.topRadius);
        if (ImGui::SliderFloat("strength (N)", &strength, 0.0f, 200.0f))
            f.strength = strength;
        if (ImGui::SliderFloat("height (m)", &height, 0.1f, 10.0f))
            f.height = height;
        if (ImGui::SliderFloat("top radius (m)", &top, std::max(r0, 0.01f), 5.0f))
            f.topRadius = top;
        float air = float(f.airSpeed), pull = float(f.axisPull);
        if (ImGui::SliderFloat("air speed (m/s, 0: off)", &air, 0.0f, 60.0f))
            f.airSpeed = air;
        if (f.airSpeed > 0.0 && ImGui::SliderFloat("axis pull (kg)", &pull, 0.0f, 5.0f))
            f.axisPull = pull;
        int axial = static_cast<int>(f.axialFalloff), radial = static_cast<int>(f.radialFalloff),
            direction = static_cast<int>(f.direction);
        if (ImGui::Combo("axial falloff", &axial, kFalloffNames, 3))
            f.axialFalloff = static_cast<Falloff>(axial);
        if (ImGui::Combo("radial falloff", &radial, kFalloffNames, 3))
            f.radialFalloff = static_cast<Falloff>(radial);
        if (ImGui::Combo("direction", &direction, kDirectionNames, 2))
            f.direction = static_cast<FlowDirection>(direction);
        float nozzle[2] = {float(f.nozzle.x), float(f.nozzle.z)};
        bool moved = ImGui::SliderFloat2("nozzle x, z (m)", nozzle, -5.0f, 5.0f);
        moved |= ImGui::SliderFloat("nozzle radius (m)", &r0, 0.0f, std::max(float(f.topRadius), 0.01f));
        if (moved) {
            f.nozzle.x = nozzle[0];
            f.nozzle.z = nozzle[1];
            f.nozzleRadius = r0;
            moveHole(world, f);
        }
        float axis[3] = {float(f.axis.x), float(f.axis.y), float(f.axis.z)};
        if (ImGui::SliderFloat3("axis", axis, -1.0f, 1.0f) && glm::length(glm::vec3(axis[0], axis[1], axis[2])) > 1e-3f)
            f.axis = glm::normalize(dvec3(axis[0], axis[1], axis[2]));
        ImGui::PopID();
    }
}

} // namespace

void drawPanel(ViewerState& state)
{
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - 10, 10), ImGuiCond_FirstUseEver, ImVec2(1, 0));
    ImGui::SetNextWindowSize(ImVec2(430, io.DisplaySize.y - 20), ImGuiCond_FirstUseEver);
    ImGui::Begin("pba");
    if (state.error) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
        ImGui::TextWrapped("%s", state.error->c_str());
        ImGui::PopStyleColor();
        if (ImGui::Button("reset"))
            state.reset();
    }
    sceneSection(state);
    if (ImGui::CollapsingHeader("time", ImGuiTreeNodeFlags_DefaultOpen))
        timeSection(state);
    if (ImGui::CollapsingHeader("view", ImGuiTreeNodeFlags_DefaultOpen))
        viewSection(state);
    if (ImGui::CollapsingHeader("particles", ImGuiTreeNodeFlags_DefaultOpen))
        particlesSection(state);
    if (ImGui::CollapsingHeader("blow dryer", ImGuiTreeNodeFlags_DefaultOpen))
        dryerSection(state);
    if (ImGui::CollapsingHeader("plots", ImGuiTreeNodeFlags_DefaultOpen))
        plotsSection(state);
    ImGui::TextDisabled("drag: orbit  right-drag/shift-drag: pan  wheel: zoom  c: camera  Esc: quit");
    ImGui::End();
}

} // namespace pba::app
