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
    buildDrawList(world, initial, alpha, settings, trails, m_list);
    m_context.bindForDrawing();
    m_renderer.draw(m_list, m_camera, width(), height());
    if (m_imgui) {
        // ImGui sizes an auto-resizing window during its first frame and shows it from the
        // second, so the very first picture runs the legend twice.
        for (int pass = m_legendShown ? 1 : 0; pass < 2; ++pass) {
            m_imgui->beginFrame(width(), height(), 1.0f / 60.0f);
            drawLegend(world, sceneName, dt, drawnTime(world, alpha, settings.interpolate), true, &settings.fabric);
            m_imgui->endFrame();
        }
        m_legendShown = true;
    }
    return m_context.readPixels();
}

std::vector<std::uint8_t> OffscreenRenderer::renderList(const DrawList& list)
{
    m_context.bindForDrawing();
    m_renderer.draw(list, m_camera, width(), height());
    return m_context.readPixels();
}

} // namespace pba::render
