#pragma once
// Dear ImGui on top of the scene: the legend in rendered images and videos, and the whole
// control panel in the viewer. The same ImGui code runs in a window (GLFW backend) and
// headless (display size set by hand).
#include <string>

#include <glm/glm.hpp>

#include "pba/fabric.hpp"
#include "render/camera.hpp"

struct GLFWwindow;

namespace pba {
class World;
}

namespace pba::render {

class ImGuiLayer {
public:
    /// With a window: GLFW input; without: headless, for rendered frames.
    explicit ImGuiLayer(GLFWwindow* window = nullptr);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    void beginFrame(int width, int height, float deltaTime);
    void endFrame();

private:
    bool m_windowed;
};

/// A small box naming the scene, the time, the collision rules that apply, and each body in its
/// colour with its integrator (a rope or cloth of `fabric` on one line of its own, not particle by
/// particle); `compact` shows the first few, as many as a quarter of the picture's height holds.
/// `sceneWidth`: the width the scene is drawn in (the viewer's, beside its panel; 0: the whole
/// display), which long lines wrap within. Returns the box's size in pixels (ImGui knows it from
/// the legend's second frame on).
/// The legend's distance from the picture's left and bottom edges, pixels.
inline constexpr float kLegendMargin = 10.0f;

/// The starting camera moved so that the picture of `initial`'s room (or its framed bodies) keeps
/// out of the legend's corner, for a legend of drawLegend's `size` on a `width` x `height` picture.
OrbitCamera clearOfLegend(const OrbitCamera& camera, const World& initial, int width, int height,
                          const glm::vec2& size);

glm::vec2 drawLegend(const World& world, const std::string& sceneName, double dt, double shownTime, bool compact = false,
                     const FabricLayout* fabric = nullptr, float sceneWidth = 0.0f);

} // namespace pba::render
