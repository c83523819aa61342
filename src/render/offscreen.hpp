#pragma once
// Everything a headless picture needs, in the order it needs it: an EGL context, the scene
// renderer, ImGui for the legend, and a camera framing the world. `pba render` and the render
// tests use this; the viewer uses the same Renderer and world_view code in a window.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/camera.hpp"
#include "render/draw_list.hpp"
#include "render/gl_context.hpp"
#include "render/overlay.hpp"
#include "render/renderer.hpp"
#include "render/world_view.hpp"

namespace pba::render {

class OffscreenRenderer {
public:
    OffscreenRenderer(int width, int height, bool legend = true);

    /// Draws the world at the clock's alpha and returns RGBA8 pixels, top row first.
    std::vector<std::uint8_t> render(const World& world, const World& initial, double alpha,
                                     const ViewSettings& settings, const Trails* trails, const std::string& sceneName,
                                     double dt);

    OrbitCamera& camera() { return m_camera; }
    /// Draws from this camera instead of the one framing the world; `framing`, it is one of the
    /// framing views, which the legend's corner may move (a camera placed by hand is kept).
    void setCamera(const OrbitCamera& camera, bool framing = false)
    {
        m_camera = camera;
        m_cameraSet = true;
        m_cameraFraming = framing;
    }
    int width() const { return m_context.width(); }
    int height() const { return m_context.height(); }
    std::string driver() const { return m_context.renderer(); }
    /// The share of the picture's height the legend's corner takes (0 without a legend); over
    /// kMostLegend, the legend is left out.
    float legendCovers() const { return m_legendCovers; }
    static constexpr float kMostLegend = 0.5f;
    /// Draws a prepared list (benchmarks, swarms) without the legend.
    std::vector<std::uint8_t> renderList(const DrawList& list);

private:
    glm::vec2 drawLegendOnce(const World& world, double alpha, const ViewSettings& settings,
                             const std::string& sceneName, double dt);

    HeadlessContext m_context;
    Renderer m_renderer;
    std::unique_ptr<ImGuiLayer> m_imgui;
    OrbitCamera m_camera;
    bool m_cameraSet = false;
    bool m_cameraFraming = true;
    bool m_legendShown = false;
    float m_legendCovers = 0.0f;
    DrawList m_list;
};

} // namespace pba::render
