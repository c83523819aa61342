#include "render_output.hpp"

#include <fmt/format.h>

#include "command.hpp"

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
    : m_kind(kind), m_width(width), m_height(height)
{
    // The path is checked here, before any rendering; a folder of frames is written beside its
    // target and swapped in whole, so no frame of a longer earlier run is left among the new.
    if (kind == OutputKind::Frames)
        m_folder = std::make_unique<io::Temporary>(io::resolveOutputFolder(out), io::Temporary::Kind::Folder);
    else
        m_out = io::resolveOutputFile(out);
    if (kind == OutputKind::Mp4)
        m_video = std::make_unique<render::VideoWriter>(m_out, width, height, fps);
}

void FrameSink::add(const std::vector<std::uint8_t>& rgba)
{
    switch (m_kind) {
    case OutputKind::Png: m_last = rgba; break;
    case OutputKind::Mp4: m_video->addFrame(rgba); break;
    case OutputKind::Frames:
        // Inside the temporary folder a frame needs no temporary of its own: the folder is
        // synced and renamed as a whole.
        io::writeFile(m_folder->path() / fmt::format("frame_{:05}.png", m_count),
                      render::encodePng(m_width, m_height, rgba));
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
    else
        m_folder->commit();
}

} // namespace pba::app
