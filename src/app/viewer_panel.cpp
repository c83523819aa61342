// The viewer's control panel. Every control changes the scene or the view through the same
// calls a program would use; nothing here touches frame time.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <imgui.h>

#include "pba/blow_dryer.hpp"
#include "lanes.hpp"
#include "viewer.hpp"
#include "viewer_rows.hpp"

namespace pba::app {

namespace {

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
    // The response is the points' rule: a scene of rigid bodies alone (contact impulses) has none.
    if (state.scene.world.planes().empty() || !state.scene.world.hasPoints())
        return;
    int response = static_cast<int>(state.scene.world.collisionResponse());
    if (ImGui::Combo("collision response", &response, kResponseNames, 3))
        state.setCollisionResponse(static_cast<CollisionResponse>(response));
}

void timeSection(ViewerState& state)
{
    if (ImGui::Button(state.paused ? "play (space)" : "pause (space)"))
        state.paused = !state.paused;
    ImGui::SameLine();
    if (ImGui::Button("step (.)"))
        state.apply(ViewerCommand::Step);
    ImGui::SameLine();
    if (ImGui::Button("reset (r)"))
        state.reset();
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Restart with the settings chosen here (integrators, e, dryer, dt, collisions)");
    ImGui::SameLine();
    if (ImGui::Button("reload scene (R)"))
        state.reload();
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Restart with the scene's own settings, undoing the changes made here");
    float dt = float(state.clock.dt());
    if (ImGui::SliderFloat("dt (s)", &dt, 0.0005f, 0.1f, "%.4f", ImGuiSliderFlags_Logarithmic))
        state.setDt(dt);
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
                state.alpha(), state.scene.world.time());
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
    ImGui::Checkbox("contacts (n)", &state.settings.contacts);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Each contact point of the last step, and a line along its normal the way it pushes the "
                          "body, longer the harder it pushes");
    ImGui::SameLine();
    ImGui::Checkbox("joints (j)", &state.settings.joints);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Each joint's point on each body (a dot in the body's colour) and a hinge's axis (cyan)");
    ImGui::SameLine();
    ImGui::Checkbox("axes (a)", &state.settings.axes);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Each rigid body's axes (x red, y green, z blue), its angular velocity omega (amber "
                          "arrow) and its angular momentum L (magenta arrow)");
    bool lanes = static_cast<bool>(state.settings.ghost);
    if (ImGui::Checkbox("lanes (exact ghost)", &lanes))
        state.settings.ghost = lanes ? exactGhosts(state.initial) : nullptr;
}

/// The dryer's push and air; true if any changed.
bool dryerStrengthControls(BlowDryerField& f)
{
    bool changed = false;
    float strength = float(f.strength), air = float(f.airSpeed), pull = float(f.axisPull);
    if (ImGui::SliderFloat("strength (N)", &strength, 0.0f, 200.0f))
        f.strength = strength, changed = true;
    if (ImGui::SliderFloat("air speed (m/s)", &air, 0.0f, 60.0f))
        f.airSpeed = air, changed = true;
    if (f.airSpeed > 0.0 && ImGui::SliderFloat("axis pull (kg)", &pull, 0.0f, 5.0f))
        f.axisPull = pull, changed = true;
    int axial = static_cast<int>(f.axialFalloff), radial = static_cast<int>(f.radialFalloff),
        direction = static_cast<int>(f.direction);
    if (ImGui::Combo("axial falloff", &axial, kFalloffNames, 3))
        f.axialFalloff = static_cast<Falloff>(axial), changed = true;
    if (ImGui::Combo("radial falloff", &radial, kFalloffNames, 3))
        f.radialFalloff = static_cast<Falloff>(radial), changed = true;
    if (ImGui::Combo("direction", &direction, kDirectionNames, 2))
        f.direction = static_cast<FlowDirection>(direction), changed = true;
    return changed;
}

/// The cone's shape and place; true if any changed.
bool dryerShapeControls(BlowDryerField& f)
{
    bool changed = false;
    float height = float(f.height), r0 = float(f.nozzleRadius), top = float(f.topRadius);
    if (ImGui::SliderFloat("height (m)", &height, 0.1f, 10.0f))
        f.height = height, changed = true;
    if (ImGui::SliderFloat("top radius (m)", &top, std::max(r0, 0.01f), 5.0f))
        f.topRadius = top, changed = true;
    float nozzle[2] = {float(f.nozzle.x), float(f.nozzle.z)};
    if (ImGui::SliderFloat2("nozzle x, z (m)", nozzle, -5.0f, 5.0f))
        f.nozzle.x = nozzle[0], f.nozzle.z = nozzle[1], changed = true;
    if (ImGui::SliderFloat("nozzle radius (m)", &r0, 0.0f, std::max(float(f.topRadius), 0.01f)))
        f.nozzleRadius = r0, changed = true;
    float axis[3] = {float(f.axis.x), float(f.axis.y), float(f.axis.z)};
    if (ImGui::SliderFloat3("axis", axis, -1.0f, 1.0f) && glm::length(glm::vec3(axis[0], axis[1], axis[2])) > 1e-3f)
        f.axis = glm::normalize(dvec3(axis[0], axis[1], axis[2])), changed = true;
    return changed;
}

/// Each blow dryer's settings, set through the state so that reset keeps them.
void dryerSection(ViewerState& state)
{
    for (WorldDryer dryer : blowDryers(state.scene.world)) {
        ImGui::PushID(static_cast<int>(dryer.force));
        const bool changed = dryerStrengthControls(dryer.field);
        if (changed | dryerShapeControls(dryer.field))
            state.setDryerField(dryer.force, dryer.field);
        ImGui::PopID();
    }
}

void panelSections(ViewerState& state)
{
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
    if (ImGui::CollapsingHeader("bodies", ImGuiTreeNodeFlags_DefaultOpen))
        bodiesSection(state);
    if (!blowDryers(state.scene.world).empty() && ImGui::CollapsingHeader("blow dryer", ImGuiTreeNodeFlags_DefaultOpen))
        dryerSection(state);
    if (ImGui::CollapsingHeader("plots", ImGuiTreeNodeFlags_DefaultOpen))
        plotsSection(state);
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("drag: orbit   right-drag or shift-drag: pan   wheel: zoom   c: camera   n: contacts   "
                       "j: joints   a: axes   R: reload scene   Esc: quit");
    ImGui::PopStyleColor();
}

} // namespace

float drawPanel(ViewerState& state)
{
    // Docked at the right, the full height: the scene is drawn in the rest of the window, so the
    // panel hides none of the room. Its width can be dragged, within half the window.
    const ImGuiIO& io = ImGui::GetIO();
    const float height = io.DisplaySize.y;
    const float widest = std::max(300.0f, 0.5f * io.DisplaySize.x);
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x, 0), ImGuiCond_Always, ImVec2(1, 0));
    ImGui::SetNextWindowSize(ImVec2(std::min(430.0f, widest), height), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSizeConstraints(ImVec2(std::min(300.0f, widest), height), ImVec2(widest, height));
    const bool open = ImGui::Begin("pba", nullptr, ImGuiWindowFlags_NoMove);
    const float width = open ? ImGui::GetWindowWidth() : 0.0f;
    if (open) {
        ImGui::PushItemWidth(-ImGui::GetFontSize() * 11.0f); // room for the labels on the right
        panelSections(state);
        ImGui::PopItemWidth();
    }
    ImGui::End();
    return width;
}

} // namespace pba::app
