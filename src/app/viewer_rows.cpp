// The panel's rows and plots: each rope, cloth and other body of the scene as one row with its
// controls, the scene's totals, and the first rows' plots in their colours.
#include "viewer_rows.hpp"

#include <algorithm>
#include <array>
#include <string>

#include <fmt/format.h>
#include <imgui.h>

#include "render/rigid_view.hpp"

namespace pba::app {

namespace {

ImVec4 imColour(const glm::vec4& c) { return ImVec4(c.r, c.g, c.b, 1.0f); }

/// A menu of the methods `choices` (a particle's or a rigid body's); sets `chosen` and returns
/// true when one is picked.
template <std::size_t N>
bool integratorMenu(const std::array<Integrator, N>& choices, Integrator& chosen)
{
    bool picked = false;
    if (ImGui::BeginCombo("integrator", std::string(integratorName(chosen)).c_str())) {
        for (const Integrator integrator : choices) {
            const bool current = integrator == chosen;
            if (ImGui::Selectable(std::string(integratorName(integrator)).c_str(), current) && !current) {
                chosen = integrator;
                picked = true;
            }
        }
        ImGui::EndCombo();
    }
    return picked;
}

/// One body's controls: its integrator (a particle the study's methods, a rigid body the methods
/// for rigid bodies), restitution and friction.
void bodyControls(ViewerState& state, std::size_t i)
{
    const Body& body = state.scene.world.body(i);
    if (body.isFixed())
        return;
    const bool rigid = state.scene.world.isRigid(i);
    Integrator integrator = body.getIntegrator();
    ImGui::SetNextItemWidth(170);
    if (rigid ? integratorMenu(kRigidIntegrators, integrator) : integratorMenu(kParticleIntegrators, integrator))
        state.setIntegrator(i, integrator);
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
        Integrator integrator = first.getIntegrator();
        ImGui::SetNextItemWidth(170);
        if (integratorMenu(kParticleIntegrators, integrator))
            state.setGroupIntegrator(g, integrator);
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

} // namespace

void bodiesSection(ViewerState& state)
{
    const World& world = state.scene.world;
    const std::vector<double> now = world.energies(), start = state.initial.energies();
    const double total = render::movingEnergy(world, state.groups, now);
    const double total0 = render::movingEnergy(world, state.groups, start);
    const bool fixed = render::anyGroupFixed(world, state.groups);
    dvec3 momentum(0.0);
    bool moving = false;
    for (const render::BodyGroup& group : state.groups.groups())
        if (!render::groupFixed(world, group)) {
            moving = true;
            momentum += render::groupMomentum(world, group);
        }
    if (moving) {
        ImGui::Text("all%s: E = %.4g J   E/E0 = %.4f", fixed ? " moving" : "", total,
                    total0 != 0.0 ? total / total0 : 1.0);
        ImGui::SameLine();
        // On the next line where the panel is too narrow for it (a large momentum's digits).
        const std::string p = fmt::format("|p| = {:.3g} kg m/s", glm::length(momentum));
        if (ImGui::GetContentRegionAvail().x < ImGui::CalcTextSize(p.c_str()).x + 20.0f)
            ImGui::NewLine();
        ImGui::Text("  %s", p.c_str());
    }
    for (std::size_t s = 0; s < world.swarmCount(); ++s) // its statistics are pba sim's
        ImGui::Text("swarm %s: %zu particles", world.swarm(s).name().c_str(), world.swarm(s).size());
    if (state.watch.hasSources()) { // (as pba sim says it: the push's share, and the balance's rest)
        const double work = state.watch.sourceWork(), lost = total0 + work - total;
        ImGui::Text("     the dryer's work %.4g J   E0 + work - E = %.4g J", work, lost);
    }
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

namespace {

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

} // namespace

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

} // namespace pba::app
