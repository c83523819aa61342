#include "offscreen.hpp"

namespace pba::render {

OffscreenRenderer::OffscreenRenderer(int width, int height, bool legend) : m_context(width, height)
{
    if (legend)
        m_imgui = std::make_unique<ImGuiLayer>();
}

std::vector<std::uint8_t> OffscreenRenderer::render(const World& world, const World& initial, double alpha,
                                                    const ViewSettings& settings, const Trails* trails,
                                                    const std::string& sceneName, double dt)
{
    if (!m_cameraSet) {
        m_camera = frameWorld(initial);
        m_cameraSet = true;
    }
    m_context.bindForDrawing();
    if (m_imgui && !m_legendShown) {
        // ImGui sizes an auto-resizing window in its first frame and shows it from the second: the
        // legend is laid out twice before the first picture (the scene's drawing clears them), and
        // a framing camera then keeps the room out of its corner.
        glm::vec2 legend(0.0f);
        for (int pass = 0; pass < 2; ++pass)
            legend = drawLegendOnce(world, alpha, settings, sceneName, dt);
        // A thumbnail's legend would hide most of the scene (hanging-crate's, 88% of 320x180).
        m_legendCovers = (legend.y + kLegendMargin) / float(height());
        if (m_legendCovers > kMostLegend)
            m_imgui.reset();
        else if (m_cameraFraming)
            m_camera = clearOfLegend(m_camera, initial, width(), height(), legend);
        m_legendShown = true;
    }
    buildDrawList(world, initial, alpha, settings, trails, m_list);
    m_renderer.draw(m_list, m_camera, width(), height());
    if (m_imgui)
        drawLegendOnce(world, alpha, settings, sceneName, dt);
    return m_context.readPixels();
}

glm::vec2 OffscreenRenderer::drawLegendOnce(const World& world, double alpha, const ViewSettings& settings,
                                            const std::string& sceneName, double dt)
{
    m_imgui->beginFrame(width(), height(), 1.0f / 60.0f);
    const glm::vec2 size =
        drawLegend(world, sceneName, dt, drawnTime(world, alpha, settings.interpolate), true, &settings.fabric);
    m_imgui->endFrame();
    return size;
}

std::vector<std::uint8_t> OffscreenRenderer::renderList(const DrawList& list)
{
    m_context.bindForDrawing();
    m_renderer.draw(list, m_camera, width(), height());
    return m_context.readPixels();
}

} // namespace pba::render
