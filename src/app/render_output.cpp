#include "render_output.hpp"

#include <fmt/format.h>

#include "command.hpp"
#include "render/gl_context.hpp"

namespace pba::app {

OutputKind outputKind(const std::string& out)
{
    const std::filesystem::path path(out);
    if (!out.empty() && (out.back() == '/' || std::filesystem::is_directory(path)))
        return OutputKind::Frames;
    if (path.extension() == ".png")
        return OutputKind::Png;
    if (path.extension() == ".mp4")
        return OutputKind::Mp4;
    throw UsageError(fmt::format("--out: expected FILE.png, FILE.mp4 or DIR/, got '{}'", out));
}

FrameSink::FrameSink(OutputKind kind, const std::string& out, int width, int height, int fps)
    : m_kind(kind), m_out(out), m_width(width), m_height(height)
{
    if (kind == OutputKind::Frames) {
        std::error_code ec;
        std::filesystem::create_directories(m_out, ec);
        if (ec || !std::filesystem::is_directory(m_out))
            throw UsageError(fmt::format("--out: cannot create the directory {}", out));
        return;
    }
    const auto parent = m_out.parent_path().empty() ? std::filesystem::path(".") : m_out.parent_path();
    if (!std::filesystem::is_directory(parent))
        throw UsageError(fmt::format("{}: cannot be written: the directory {} does not exist", out, parent.string()));
    if (kind == OutputKind::Mp4) {
        try {
            m_video = std::make_unique<render::VideoWriter>(m_out, width, height, fps);
        } catch (const render::RenderError& e) {
            throw RuntimeFailure(e.what());
        }
    }
}

void FrameSink::add(const std::vector<std::uint8_t>& rgba)
{
    switch (m_kind) {
    case OutputKind::Png: m_last = rgba; break;
    case OutputKind::Mp4: m_video->addFrame(rgba); break;
    case OutputKind::Frames:
        render::writePng(m_out / fmt::format("frame_{:05}.png", m_count), m_width, m_height, rgba);
        break;
    }
    ++m_count;
}

void FrameSink::finish()
{
    if (m_kind == OutputKind::Png)
        render::writePng(m_out, m_width, m_height, m_last);
    else if (m_kind == OutputKind::Mp4)
        m_video->finish();
}

} // namespace pba::app
