#include "render_output.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>

#include <fmt/format.h>

#include "atomic_file.hpp"
#include "command.hpp"

namespace pba::app {

std::string lowerExtension(const std::string& path)
{
    // In any case: a camera's or another program's IMG.PNG is a PNG.
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

OutputKind outputKind(const std::string& out)
{
    const std::filesystem::path path(out);
    if (!out.empty() && (out.back() == '/' || std::filesystem::is_directory(path)))
        return OutputKind::Frames;
    const std::string extension = lowerExtension(out);
    if (extension == ".png")
        return OutputKind::Png;
    if (extension == ".mp4")
        return OutputKind::Mp4;
    throw UsageError(fmt::format("--out: expected FILE.png, FILE.mp4 or DIR/, got '{}'", out));
}

bool isFrameName(const std::string& name)
{
    constexpr std::string_view prefix = "frame_", suffix = ".png";
    if (name.size() < prefix.size() + 5 + suffix.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
        return false;
    return std::all_of(name.begin() + prefix.size(), name.end() - suffix.size(),
                       [](char c) { return c >= '0' && c <= '9'; });
}

FrameSink::FrameSink(OutputKind kind, const std::string& out, int width, int height, int fps)
    : m_kind(kind), m_width(width), m_height(height)
{
    // The path and the folder's frames are checked here, before any rendering. The new frames
    // replace pba's earlier ones together, and pba's frames of a longer earlier run go, so none
    // is left among the new; whatever else the folder holds stays.
    if (kind == OutputKind::Frames)
        m_folder = std::make_unique<io::FolderOutput>(out, isFrameName);
    else
        m_out = resolveWritableFile("--out", out);
    if (kind == OutputKind::Mp4)
        m_video = std::make_unique<render::VideoWriter>(m_out, width, height, fps);
}

void FrameSink::add(const std::vector<std::uint8_t>& rgba)
{
    switch (m_kind) {
    case OutputKind::Png: m_last = rgba; break;
    case OutputKind::Mp4: m_video->addFrame(rgba); break;
    case OutputKind::Frames:
        // In the staging folder a frame needs no temporary of its own: the frames are synced
        // and published together.
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
