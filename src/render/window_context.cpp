#include <epoxy/gl.h>

#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include "gl_context.hpp"

namespace pba::render {

namespace {
std::string lastGlfwError()
{
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "no description";
}
} // namespace

WindowContext::WindowContext(int width, int height, const std::string& title)
{
    if (!glfwInit())
        throw RenderError("window: GLFW could not start (is DISPLAY set? try xvfb-run, or `pba render`): " +
                          lastGlfwError());
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SAMPLES, 4);
    m_window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!m_window) {
        const std::string reason = lastGlfwError();
        glfwTerminate();
        throw RenderError("window: no OpenGL 3.3 core context from GLFW: " + reason);
    }
    glfwMakeContextCurrent(m_window);
    glfwSwapInterval(1);
}

WindowContext::~WindowContext()
{
    if (m_window)
        glfwDestroyWindow(m_window);
    glfwTerminate();
}

bool WindowContext::shouldClose() const { return glfwWindowShouldClose(m_window); }

void WindowContext::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(m_window, &width, &height); }

void WindowContext::bindForDrawing()
{
    int width = 0, height = 0;
    framebufferSize(width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
}

std::vector<std::uint8_t> WindowContext::readPixels()
{
    int width = 0, height = 0;
    framebufferSize(width, height);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    return readFramebuffer(width, height);
}

void WindowContext::swap() { glfwSwapBuffers(m_window); }

} // namespace pba::render
