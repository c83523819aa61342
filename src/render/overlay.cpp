#include "overlay.hpp"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "body_groups.hpp"
#include "collision_note.hpp"
#include "world_view.hpp"
#include "pba/particle.hpp"
#include "pba/world.hpp"

namespace pba::render {

ImGuiLayer::ImGuiLayer(GLFWwindow* window) : m_windowed(window != nullptr)
{
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // no imgui.ini left behind in the user's directory
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 4.0f;
    if (window)
        ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core"); // 1.86 defaults to GLSL 130, refused by core profiles
}

ImGuiLayer::~ImGuiLayer()
{
    ImGui_ImplOpenGL3_Shutdown();
    if (m_windowed)
        ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void ImGuiLayer::beginFrame(int width, int height, float deltaTime)
{
    ImGui_ImplOpenGL3_NewFrame();
    if (m_windowed) {
        ImGui_ImplGlfw_NewFrame();
    } else {
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(float(width), float(height));
        io.DeltaTime = deltaTime > 0.0f ? deltaTime : 1.0f / 60.0f;
    }
    ImGui::NewFrame();
}

void ImGuiLayer::endFrame()
{
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

namespace {

/// The integrator a group's moving bodies use, or "fixed".
std::string integratorText(const World& world, const BodyGroup& group)
{
    for (const std::size_t i : group.members)
        if (!world.body(i).isFixed())
            return std::string(integratorName(world.body(i).getIntegrator()));
    return "fixed";
}

void bullet(const glm::vec4& c)
{
    ImGui::TextColored(ImVec4(c.r, c.g, c.b, 1.0f), "o");
    ImGui::SameLine();
}

/// Which collision rule applies to this scene's bodies, readable on the picture: wrapped within
/// `width`, the scene's part of it.
void collisionLine(const World& world, float width)
{
    const std::string note = collisionNote(world);
    if (note.empty())
        return;
    ImGui::PushTextWrapPos(std::max(200.0f, width - 40.0f));
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.80f, 0.86f, 0.95f, 1.0f));
    ImGui::TextWrapped("%s", note.c_str());
    ImGui::PopStyleColor();
    ImGui::PopTextWrapPos();
}

/// One line per group in its colour: a body with its integrator (and its mass where masses
/// differ), a rope or cloth as one line.
void groupLines(const World& world, const BodyGroups& groups, bool compact)
{
    bool massesDiffer = false, balls = false; // then each mass is given, which sets a ball's drawn size
    std::optional<double> mass;
    for (const BodyGroup& g : groups.groups()) {
        if (g.fabric())
            continue;
        const Body& body = world.body(g.members.front());
        massesDiffer = massesDiffer || (mass && *mass != body.getMass());
        mass = body.getMass();
        // A particle with a radius is drawn at its size, not by its mass.
        const auto* particle = dynamic_cast<const Particle*>(&body);
        balls = balls || (particle && particle->getRadius() == 0.0);
    }
    // Compact, the legend keeps to about a quarter of the picture's height (8 lines at 720 pixels,
    // 3 at 360), so a small picture's scene is not hidden behind a list of boxes.
    const int fits = int(0.25f * ImGui::GetIO().DisplaySize.y / ImGui::GetTextLineHeightWithSpacing()) - 2;
    const std::size_t shown = compact ? std::min<std::size_t>(groups.size(), std::clamp(fits, 2, 8)) : groups.size();
    for (std::size_t g = 0; g < shown; ++g) {
        const BodyGroup& group = groups[g];
        bullet(group.colour);
        const std::string integrator = integratorText(world, group);
        if (!group.fabric() && massesDiffer)
            ImGui::Text("%s  %.3g kg  (%s)", group.label.c_str(), world.body(group.members.front()).getMass(),
                        integrator.c_str());
        else
            ImGui::Text("%s  (%s)", group.label.c_str(), integrator.c_str());
    }
    if (massesDiffer && balls)
        ImGui::TextDisabled("balls of one density: the heavier, the larger");
    if (shown < groups.size())
        ImGui::Text("... and %zu more", groups.size() - shown);
}

} // namespace

OrbitCamera clearOfLegend(const OrbitCamera& camera, const World& initial, int width, int height,
                          const glm::vec2& size)
{
    const FramedBox box = framedBox(initial);
    return clearOfCorner(camera, box.lo, box.hi, width, height, size + glm::vec2(kLegendMargin));
}

glm::vec2 drawLegend(const World& world, const std::string& sceneName, double dt, double shownTime, bool compact,
                     const FabricLayout* fabric, float sceneWidth)
{
    // Bottom left: the room's upper half, where balls fly and hover, stays in view (and a picture's
    // framing camera keeps the room out of the box: OrbitCamera::clearOfCorner).
    ImGui::SetNextWindowPos(ImVec2(kLegendMargin, ImGui::GetIO().DisplaySize.y - kLegendMargin), ImGuiCond_Always,
                            ImVec2(0, 1));
    ImGui::SetNextWindowBgAlpha(0.65f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
    glm::vec2 size(0.0f);
    if (ImGui::Begin("legend", nullptr, flags)) {
        ImGui::Text("%s   t = %.2f s   dt = %g s", sceneName.c_str(), shownTime, dt);
        collisionLine(world, sceneWidth > 0.0f ? sceneWidth : ImGui::GetIO().DisplaySize.x);
        const BodyGroups groups(world, fabric ? *fabric : FabricLayout{});
        groupLines(world, groups, compact);
        for (std::size_t s = 0; s < world.swarmCount(); ++s) {
            bullet(groups.swarmColour(s));
            ImGui::Text("swarm %s: %zu particles (%s)", world.swarm(s).name().c_str(), world.swarm(s).size(),
                        std::string(integratorName(world.swarm(s).integrator())).c_str());
        }
        size = glm::vec2(ImGui::GetWindowSize().x, ImGui::GetWindowSize().y);
    }
    ImGui::End();
    return size;
}

} // namespace pba::render
