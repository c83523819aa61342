#include "image_io.hpp"

#include <unistd.h>

#include <cstdlib>

#include <fmt/format.h>
#include <stb_image_write.h>

#include "gl_context.hpp"

namespace pba::render {

namespace {
std::filesystem::path temporaryBeside(const std::filesystem::path& target, const char* extension)
{
    std::filesystem::path temporary = target;
    temporary += fmt::format(".tmp-{}{}", ::getpid(), extension);
    return temporary;
}
} // namespace

void writePng(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgba)
{
    const auto temporary = temporaryBeside(path, ".png");
    if (!stbi_write_png(temporary.c_str(), width, height, 4, rgba.data(), width * 4)) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw RenderError(fmt::format("{}: cannot write the PNG (does the directory exist?)", path.string()));
    }
    std::filesystem::rename(temporary, path);
}

bool ffmpegAvailable() { return std::system("command -v ffmpeg >/dev/null 2>&1") == 0; }

VideoWriter::VideoWriter(std::filesystem::path target, int width, int height, int fps)
    : m_target(std::move(target)), m_temporary(temporaryBeside(m_target, ".mp4")),
      m_frameBytes(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4)
{
    if (!ffmpegAvailable())
        throw RenderError("ffmpeg is not installed: install the Debian package ffmpeg (scripts/install-deps.sh does)");
    // Frames arrive top row first (already flipped), so no -vf vflip. yuv420p needs even sizes.
    const std::string command = fmt::format(
        "ffmpeg -nostdin -y -loglevel error -f rawvideo -pixel_format rgba -video_size {}x{} -framerate {} -i - "
        "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -preset veryfast -pix_fmt yuv420p -movflags +faststart "
        "-f mp4 '{}'",
        width, height, fps, m_temporary.string());
    m_pipe = ::popen(command.c_str(), "w");
    if (!m_pipe)
        throw RenderError("cannot start ffmpeg");
}

VideoWriter::~VideoWriter()
{
    if (m_pipe) {
        ::pclose(m_pipe);
        std::error_code ignored;
        std::filesystem::remove(m_temporary, ignored);
    }
}

void VideoWriter::addFrame(const std::vector<std::uint8_t>& rgba)
{
    if (rgba.size() != m_frameBytes || std::fwrite(rgba.data(), 1, rgba.size(), m_pipe) != rgba.size())
        throw RenderError("ffmpeg stopped accepting frames");
}

void VideoWriter::finish()
{
    const int status = ::pclose(m_pipe);
    m_pipe = nullptr;
    if (status != 0) {
        std::error_code ignored;
        std::filesystem::remove(m_temporary, ignored);
        throw RenderError(fmt::format("ffmpeg failed to encode {} (exit status {})", m_target.string(), status));
    }
    std::filesystem::rename(m_temporary, m_target);
}

} // namespace pba::render
