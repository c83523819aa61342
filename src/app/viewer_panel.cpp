// The viewer's control panel. Every control changes the scene or the view through the same
// calls a program would use; nothing here touches frame time.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <imgui.h>

#include "pba/blow_dryer.hpp"
#include "lanes.hpp"
#include "render/rigid_view.hpp"
#include "viewer.hpp"

namespace pba::app {

namespace {

constexpr const char* kIntegratorNames[] = {"forward-euler", "semi-implicit-euler", "velocity-verlet", "rk4",
                                            "implicit-gyroscopic"};
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

ImVec4 imColour(const glm::vec4& c) { return ImVec4(c.r, c.g, c.b, 1.0f); }

/// One body's controls: its integrator (a rigid body may take the fifth method, its rotation's
/// implicit gyroscopic step; a particle the four of the study), restitution and friction.
void bodyControls(ViewerState& state, std::size_t i)
{
    const Body& body = state.scene.world.body(i);
    if (body.isFixed())
        return;
    const bool rigid = state.scene.world.isRigid(i);
    int integrator = static_cast<int>(body.getIntegrator());
    ImGui::SetNextItemWidth(170);
    if (ImGui::Combo("integrator", &integrator, kIntegratorNames, rigid ? 5 : 4))
        state.setIntegrator(i, static_cast<Integrator>(integrator));
    ImGui::SameLine();
    float e = float(body.getCor());
    ImGui::SetNextItemWidth(100);
    if (ImGui::SliderFloat("e", &e, 0.0f, 1.0f, "%.2f"))
        state.setRestitution(i, e);
    if (rigid) { // on a line of its own: the panel is too narrow for a third control
        float mu = float(static_cast<const RigidBody&>(body).getFriction());
        ImGui::SetNextItemWidth(170);
        if (ImGui::SliderFloat("friction (mu)", &mu, 0.0f, 1.5f, "%.2f"))
            state.setFriction(i, mu);
    }
}

/// A rope's or cloth's particles, listed when its row is opened (a clipper: a cloth may have
/// 16,384), each with its height and energy over its start.
void memberList(const ViewerState& state, const render::BodyGroup& group, const std::vector<double>& now,
                const std::vector<double>& start)
{
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(group.members.size()));
    while (clipper.Step())
        for (int k = clipper.DisplayStart; k < clipper.DisplayEnd; ++k) {
            const std::size_t i = group.members[static_cast<std::size_t>(k)];
            const Body& body = state.scene.world.body(i);
            ImGui::Text("%s  y = %.3f m   E/E0 = %.4f%s", body.getName().c_str(), body.getPos().y,
                        start[i] != 0.0 ? now[i] / start[i] : 1.0, body.isFixed() ? "   (pinned)" : "");
        }
}

/// A rope or cloth as one row: its name, particle count, total energy, and one integrator menu
/// and restitution for the whole system; opened, its particles.
void fabricRow(ViewerState& state, std::size_t g, const std::vector<double>& now, const std::vector<double>& start)
{
    const render::BodyGroup& group = state.groups[g];
    const double e = render::groupEnergy(group, now), e0 = render::groupEnergy(group, start);
    const bool open = ImGui::TreeNode("##members", "%s", "");
    ImGui::SameLine();
    ImGui::TextColored(imColour(group.colour), "%s", group.label.c_str());
    ImGui::Text("  E = %.4g J   E/E0 = %.4f", e, e0 != 0.0 ? e / e0 : 1.0);
    const auto moving = std::find_if(group.members.begin(), group.members.end(),
                                     [&](std::size_t i) { return !state.scene.world.body(i).isFixed(); });
    if (moving != group.members.end()) {
        const Body& first = state.scene.world.body(*moving);
        int integrator = static_cast<int>(first.getIntegrator());
        ImGui::SetNextItemWidth(170);
        if (ImGui::Combo("integrator", &integrator, kIntegratorNames, 4))
            state.setGroupIntegrator(g, static_cast<Integrator>(integrator));
        ImGui::SameLine();
        float cor = float(first.getCor());
        ImGui::SetNextItemWidth(100);
        if (ImGui::SliderFloat("e", &cor, 0.0f, 1.0f, "%.2f"))
            state.setGroupRestitution(g, cor);
    }
    if (open) {
        memberList(state, group, now, start);
        ImGui::TreePop();
    }
}

/// A row per group: a rope or cloth as one, every other body with its own controls; then the
/// scene's totals.
void bodiesSection(ViewerState& state)
{
    const World& world = state.scene.world;
    const std::vector<double> now = world.energies(), start = state.initial.energies();
    double total = 0.0, total0 = 0.0;
    dvec3 momentum(0.0);
    for (const render::BodyGroup& group : state.groups.groups()) {
        total += render::groupEnergy(group, now);
        total0 += render::groupEnergy(group, start);
        momentum += render::groupMomentum(world, group);
    }
    ImGui::Text("all: E = %.4g J   E/E0 = %.4f   |p| = %.3g kg m/s", total, total0 != 0.0 ? total / total0 : 1.0,
                glm::length(momentum));
    constexpr std::size_t kRows = 12;
    const std::size_t shown = std::min(state.groups.size(), kRows);
    for (std::size_t g = 0; g < shown; ++g) {
        ImGui::PushID(static_cast<int>(g));
        const render::BodyGroup& group = state.groups[g];
        if (group.fabric()) {
            fabricRow(state, g, now, start);
        } else {
            const std::size_t i = group.members.front();
            ImGui::TextColored(imColour(state.groups.bodyColour(i)), "%s", group.label.c_str());
            ImGui::SameLine();
            ImGui::Text("  y = %.3f m   E/E0 = %.4f", world.body(i).getPos().y, start[i] != 0.0 ? now[i] / start[i] : 1.0);
            bodyControls(state, i);
        }
        ImGui::PopID();
    }
    if (shown < state.groups.size())
        ImGui::TextDisabled("... and %zu more (pba sim lists them all)", state.groups.size() - shown);
}

/// A plot with its y scale: the label above it, where it is never cut off; the ends of the range
/// written at its top and bottom left; and a margin, so that a flat line (E/E0 = 1 from the start)
/// is drawn inside the frame rather than on its bottom edge. `minSpan` keeps rounding noise from
/// filling the plot.
void plotWithScale(const char* id, const std::string& label, const std::vector<float>& values, const char* format,
                   float minSpan)
{
    ImGui::TextUnformatted(label.c_str());
    float lo = values.empty() ? 0.0f : *std::min_element(values.begin(), values.end());
    float hi = values.empty() ? 0.0f : *std::max_element(values.begin(), values.end());
    const float middle = 0.5f * (lo + hi), half = 0.55f * std::max(hi - lo, minSpan);
    lo = middle - half;
    hi = middle + half;
    ImGui::PlotLines(id, values.data(), static_cast<int>(values.size()), 0, nullptr, lo, hi,
                     ImVec2(ImGui::GetContentRegionAvail().x, 52));
    const ImVec2 top = ImGui::GetItemRectMin(), bottom = ImGui::GetItemRectMax();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImU32 colour = ImGui::GetColorU32(ImGuiCol_TextDisabled);
    draw->AddText(ImVec2(top.x + 4, top.y + 1), colour, fmt::format(fmt::runtime(format), hi).c_str());
    draw->AddText(ImVec2(top.x + 4, bottom.y - ImGui::GetFontSize() - 1), colour,
                  fmt::format(fmt::runtime(format), lo).c_str());
}

/// Omega's three components in the body's frame on one plot, in the colours of the body's axes
/// (x red, y green, z blue), one scale for the three.
void spinPlot(const std::array<Series, 3>& spin)
{
    ImGui::TextUnformatted("omega in the body's frame (rad/s): x red, y green, z blue");
    float lo = 0.0f, hi = 0.0f;
    for (const Series& s : spin)
        for (const float v : s.values())
            lo = std::min(lo, v), hi = std::max(hi, v);
    const float middle = 0.5f * (lo + hi), half = 0.55f * std::max(hi - lo, 0.1f);
    lo = middle - half;
    hi = middle + half;
    const ImVec2 size(ImGui::GetContentRegionAvail().x, 64);
    const ImVec2 top = ImGui::GetCursorScreenPos(), bottom(top.x + size.x, top.y + size.y);
    ImGui::Dummy(size);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(top, bottom, ImGui::GetColorU32(ImGuiCol_FrameBg));
    const float zero = bottom.y - (0.0f - lo) / (hi - lo) * size.y;
    if (zero > top.y && zero < bottom.y)
        draw->AddLine(ImVec2(top.x, zero), ImVec2(bottom.x, zero), ImGui::GetColorU32(ImGuiCol_TextDisabled));
    for (int k = 0; k < 3; ++k) {
        const std::vector<float>& v = spin[k].values();
        const glm::vec4 c = render::kAxisColours[k];
        for (std::size_t n = 1; n < v.size(); ++n) {
            auto at = [&](std::size_t m) {
                return ImVec2(top.x + size.x * float(m) / float(Series::kLength - 1),
                              bottom.y - (v[m] - lo) / (hi - lo) * size.y);
            };
            draw->AddLine(at(n - 1), at(n), ImGui::GetColorU32(ImVec4(c.r, c.g, c.b, 1.0f)), 1.5f);
        }
    }
    const ImU32 text = ImGui::GetColorU32(ImGuiCol_TextDisabled);
    draw->AddText(ImVec2(top.x + 4, top.y + 1), text, fmt::format("{:.2f}", hi).c_str());
    draw->AddText(ImVec2(top.x + 4, bottom.y - ImGui::GetFontSize() - 1), text, fmt::format("{:.2f}", lo).c_str());
}

/// The first groups' plots, each line in its group's colour.
void plotsSection(const ViewerState& state)
{
    for (std::size_t g = 0; g < state.plots.size(); ++g) {
        const render::BodyGroup& group = state.groups[g];
        const GroupPlots& p = state.plots[g];
        ImGui::PushID(static_cast<int>(g));
        ImGui::PushStyleColor(ImGuiCol_PlotLines, imColour(group.colour));
        for (const PlotKind kind : plotKinds(state.scene.world, group)) {
            switch (kind) {
            case PlotKind::Height:
                plotWithScale("##height", fmt::format("height of {} (m)", group.name), p.height.values(), "{:.2f}", 0.1f);
                break;
            case PlotKind::EnergyRatio:
                plotWithScale("##energy",
                              group.fabric() ? fmt::format("E/E0 of {} {}, all its particles",
                                                           group.kind == render::BodyGroup::Kind::Rope ? "rope" : "cloth",
                                                           group.name)
                                             : fmt::format("E/E0 of {}", group.name),
                              p.energyRatio.values(), "{:.3f}", 0.01f);
                break;
            case PlotKind::BodySpin: spinPlot(p.spin); break;
            }
        }
        ImGui::PopStyleColor();
        ImGui::PopID();
    }
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
