#include "overlay.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "pba/world.hpp"
#include "world_view.hpp"

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

void fabricLegend(const World& world, const FabricLayout& fabric)
{
    auto line = [&](std::size_t first, const std::string& text) {
        if (first >= world.bodyCount())
            return;
        const glm::vec4 c = integratorColour(world.body(first).getIntegrator());
        ImGui::TextColored(ImVec4(c.r, c.g, c.b, 1.0f), "o");
        ImGui::SameLine();
        ImGui::Text("%s  (%s)", text.c_str(), std::string(integratorName(world.body(first).getIntegrator())).c_str());
    };
    for (const RopeLayout& rope : fabric.ropes)
        if (!rope.particles.empty())
            line(rope.particles.front(),
                 "rope " + rope.name + ": " + std::to_string(rope.particles.size()) + " particles");
    for (const ClothLayout& cloth : fabric.cloths)
        line(cloth.first, "cloth " + cloth.name + ": " + std::to_string(cloth.width) + " x " +
                              std::to_string(cloth.height) + " particles");
}

} // namespace

void drawLegend(const World& world, const std::string& sceneName, double dt, double shownTime, bool compact,
                const FabricLayout* fabric)
{
    // Bottom left: the room's upper half, where balls fly and hover, stays in view.
    ImGui::SetNextWindowPos(ImVec2(10, ImGui::GetIO().DisplaySize.y - 10), ImGuiCond_Always, ImVec2(0, 1));
    ImGui::SetNextWindowBgAlpha(0.65f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
    if (ImGui::Begin("legend", nullptr, flags)) {
        ImGui::Text("%s   t = %.2f s   dt = %g s", sceneName.c_str(), shownTime, dt);
        if (!world.planes().empty()) { // wrapped within the picture, however narrow
            ImGui::PushTextWrapPos(std::max(200.0f, ImGui::GetIO().DisplaySize.x - 40.0f));
            ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
            // The collision response is the points' rule: rigid bodies meet the room with contact
            // impulses whatever it is.
            if (world.hasPoints())
                ImGui::TextWrapped("collisions: %s%s%s",
                                   std::string(collisionResponseSummary(world.collisionResponse())).c_str(),
                                   world.coupledBodiesReflect() ? "; bodies joined by springs: reflect" : "",
                                   world.hasRigidBodies() ? "; rigid bodies: contact impulses" : "");
            else
                ImGui::TextWrapped("contacts: impulses with each body's restitution and friction");
            ImGui::PopStyleColor();
            ImGui::PopTextWrapPos();
        }
        if (fabric)
            fabricLegend(world, *fabric);
        // The particles that are no rope's or cloth's, each on its line.
        std::vector<std::size_t> loose;
        const std::vector<bool> member = fabricMembers(world, fabric ? *fabric : FabricLayout{});
        for (std::size_t i = 0; i < world.bodyCount(); ++i)
            if (!member[i])
                loose.push_back(i);
        const std::size_t shown = compact ? std::min<std::size_t>(loose.size(), 8) : loose.size();
        bool massesDiffer = false; // then the legend says each mass, which sets its drawn size
        for (const std::size_t i : loose)
            massesDiffer = massesDiffer || world.body(i).getMass() != world.body(loose.front()).getMass();
        for (std::size_t k = 0; k < shown; ++k) {
            const Body& body = world.body(loose[k]);
            const glm::vec4 c = bodyColour(body);
            ImGui::TextColored(ImVec4(c.r, c.g, c.b, 1.0f), "o");
            ImGui::SameLine();
            const std::string integrator = body.isFixed() ? "fixed" : std::string(integratorName(body.getIntegrator()));
            if (massesDiffer)
                ImGui::Text("%s  %g kg  (%s)", body.getName().c_str(), body.getMass(), integrator.c_str());
            else
                ImGui::Text("%s  (%s)", body.getName().c_str(), integrator.c_str());
        }
        bool balls = false; // particles, drawn as balls sized by mass (a rigid body is drawn as its shape)
        for (const std::size_t i : loose)
            balls = balls || !world.isRigid(i);
        if (massesDiffer && balls)
            ImGui::TextDisabled("balls of one density: the heavier, the larger");
        if (shown < loose.size())
            ImGui::Text("... and %zu more", loose.size() - shown);
        for (std::size_t s = 0; s < world.swarmCount(); ++s) {
            const glm::vec4 c = integratorColour(world.swarm(s).integrator());
            ImGui::TextColored(ImVec4(c.r, c.g, c.b, 1.0f), "o");
            ImGui::SameLine();
            ImGui::Text("swarm %s: %zu particles (%s)", world.swarm(s).name().c_str(), world.swarm(s).size(),
                        std::string(integratorName(world.swarm(s).integrator())).c_str());
        }
    }
    ImGui::End();
}

} // namespace pba::render
