#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <fmt/format.h>

#include "gl_context.hpp"

namespace pba::render {

namespace {
std::string eglErrorText() { return fmt::format("EGL error 0x{:04x}", eglGetError()); }
} // namespace

HeadlessContext::HeadlessContext(int width, int height, int samples) : m_width(width), m_height(height)
{
    if (width <= 0 || height <= 0)
        throw RenderError(fmt::format("cannot render a {}x{} image", width, height));
    // Surfaceless Mesa: no X display, no GPU needed (llvmpipe rasterises on the CPU).
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY)
        throw RenderError("headless OpenGL: eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA) found no "
                          "display (is Mesa's libegl-mesa0 installed?): " + eglErrorText());
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor))
        throw RenderError("headless OpenGL: eglInitialize on the surfaceless Mesa display failed: " + eglErrorText());
    m_display = display;
    if (!eglBindAPI(EGL_OPENGL_API))
        throw RenderError("headless OpenGL: eglBindAPI(EGL_OPENGL_API) failed: " + eglErrorText());
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT)
        throw RenderError("headless OpenGL: no OpenGL 3.3 core context without a config (EGL_KHR_no_config_context): " +
                          eglErrorText());
    m_context = context;
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
        throw RenderError("headless OpenGL: eglMakeCurrent without a surface failed: " + eglErrorText());
    createFramebuffers(samples);
}

void HeadlessContext::createFramebuffers(int samples)
{
    GLint maxSamples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    samples = std::min(samples, static_cast<int>(maxSamples));
    m_multisampled = samples > 1;
    glGenRenderbuffers(1, &m_colour);
    glBindRenderbuffer(GL_RENDERBUFFER, m_colour);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, m_multisampled ? samples : 0, GL_RGBA8, m_width, m_height);
    glGenRenderbuffers(1, &m_depth);
    glBindRenderbuffer(GL_RENDERBUFFER, m_depth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, m_multisampled ? samples : 0, GL_DEPTH24_STENCIL8, m_width,
                                     m_height);
    glGenFramebuffers(1, &m_drawFbo);
    glBindFramebuffer(GL_FRAMEBUFFER, m_drawFbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m_colour);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, m_depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw RenderError(fmt::format("headless OpenGL: the {}x{} framebuffer object ({} samples) is incomplete",
                                      m_width, m_height, samples));
    glGenRenderbuffers(1, &m_resolveColour);
    glBindRenderbuffer(GL_RENDERBUFFER, m_resolveColour);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, m_width, m_height);
    glGenFramebuffers(1, &m_resolveFbo);
    glBindFramebuffer(GL_FRAMEBUFFER, m_resolveFbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m_resolveColour);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw RenderError("headless OpenGL: the resolve framebuffer object is incomplete");
}

HeadlessContext::~HeadlessContext()
{
    if (m_context) {
        glDeleteFramebuffers(1, &m_drawFbo);
        glDeleteFramebuffers(1, &m_resolveFbo);
        glDeleteRenderbuffers(1, &m_colour);
        glDeleteRenderbuffers(1, &m_depth);
        glDeleteRenderbuffers(1, &m_resolveColour);
        eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(m_display, m_context);
    }
    if (m_display)
        eglTerminate(m_display);
}

void HeadlessContext::bindForDrawing()
{
    glBindFramebuffer(GL_FRAMEBUFFER, m_drawFbo);
    glViewport(0, 0, m_width, m_height);
}

std::vector<std::uint8_t> HeadlessContext::readPixels()
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m_drawFbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m_resolveFbo);
    glBlitFramebuffer(0, 0, m_width, m_height, 0, 0, m_width, m_height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m_resolveFbo);
    auto pixels = readFramebuffer(m_width, m_height);
    glBindFramebuffer(GL_FRAMEBUFFER, m_drawFbo);
    return pixels;
}

std::string HeadlessContext::renderer() const
{
    const auto* text = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return text ? text : "unknown";
}

std::vector<std::uint8_t> readFramebuffer(int width, int height)
{
    const std::size_t row = static_cast<std::size_t>(width) * 4;
    std::vector<std::uint8_t> pixels(row * static_cast<std::size_t>(height));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    // OpenGL's rows run bottom-up; images run top-down.
    for (int y = 0; y < height / 2; ++y)
        std::swap_ranges(pixels.begin() + static_cast<std::ptrdiff_t>(y * row),
                         pixels.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                         pixels.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row));
    return pixels;
}

} // namespace pba::render
