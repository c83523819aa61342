#pragma once
// Where OpenGL comes from. The drawing code does not care: a GLFW window for `pba view`,
// an EGL surfaceless context with a framebuffer object for `pba render` and the tests
// (GLFW 3.3 cannot start without a display; Mesa's surfaceless EGL needs none).
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

struct GLFWwindow;

namespace pba::render {

/// Context creation, shader or framebuffer failure; the message says what was tried.
class RenderError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// An OpenGL 3.3+ core context rendering off screen into a framebuffer object.
class HeadlessContext {
public:
    /// Throws RenderError naming each step that failed (display, initialise, context, FBO).
    HeadlessContext(int width, int height, int samples = 4);
    ~HeadlessContext();
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;

    int width() const { return m_width; }
    int height() const { return m_height; }
    /// Binds the framebuffer to draw into and sets the viewport.
    void bindForDrawing();
    /// Resolves multisampling and returns RGBA8 pixels, top row first.
    std::vector<std::uint8_t> readPixels();
    /// The renderer string of the driver, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    std::string renderer() const;

private:
    void createFramebuffers(int samples);

    int m_width;
    int m_height;
    void* m_display = nullptr;
    void* m_context = nullptr;
    unsigned m_drawFbo = 0, m_resolveFbo = 0;
    unsigned m_colour = 0, m_depth = 0, m_resolveColour = 0;
    bool m_multisampled = false;
};

/// A GLFW window with an OpenGL 3.3 core context.
class WindowContext {
public:
    /// Throws RenderError if GLFW cannot start (no display?) or the context cannot be made.
    WindowContext(int width, int height, const std::string& title);
    ~WindowContext();
    WindowContext(const WindowContext&) = delete;
    WindowContext& operator=(const WindowContext&) = delete;

    GLFWwindow* window() const { return m_window; }
    bool shouldClose() const;
    void framebufferSize(int& width, int& height) const;
    /// Binds the default framebuffer and sets the viewport to the window's size.
    void bindForDrawing();
    /// RGBA8 pixels of the back buffer, top row first (call before swap).
    std::vector<std::uint8_t> readPixels();
    void swap();

private:
    GLFWwindow* m_window = nullptr;
};

/// Reads the bound read framebuffer into RGBA8, flipping rows so the top row comes first.
std::vector<std::uint8_t> readFramebuffer(int width, int height);

} // namespace pba::render
