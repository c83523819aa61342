#include "image_io.hpp"

#include <unistd.h>

#include <fmt/format.h>
#include <stb_image_write.h>

#include "mp4_check.hpp"

namespace pba::render {

std::string encodePng(int width, int height, const std::vector<std::uint8_t>& rgba)
{
    std::string bytes;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
    };
    if (!stbi_write_png_to_func(append, &bytes, width, height, 4, rgba.data(), width * 4))
        throw io::WriteError("cannot encode the PNG");
    return bytes;
}

void writePng(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgba)
{
    io::writeFileAtomically(path, encodePng(width, height, rgba));
}

bool ffmpegAvailable() { return io::findProgram("ffmpeg").has_value(); }

VideoWriter::VideoWriter(const std::filesystem::path& target, int width, int height, int fps)
    : m_video(target, io::Temporary::Kind::File),
      m_log(std::filesystem::temp_directory_path() / fmt::format("pba-ffmpeg-{}.log", ::getpid()),
            io::Temporary::Kind::File),
      m_frameBytes(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4)
{
    if (!ffmpegAvailable())
        throw io::WriteError("ffmpeg is not installed: install the Debian package ffmpeg (scripts/install-deps.sh does)");
    // Frames arrive top row first (already flipped), so no vflip. yuv420p needs even sizes. The
    // output is named as a file: URL of an absolute path, so no name can read as an option or
    // another protocol.
    const std::string output = "file:" + std::filesystem::absolute(m_video.path()).string();
    m_ffmpeg = std::make_unique<io::ChildProcess>(
        std::vector<std::string>{"ffmpeg", "-nostdin", "-y", "-loglevel", "error", "-f", "rawvideo", "-pixel_format",
                                 "rgba", "-video_size", fmt::format("{}x{}", width, height), "-framerate",
                                 std::to_string(fps), "-i", "pipe:0", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v",
                                 "libx264", "-preset", "veryfast", "-pix_fmt", "yuv420p", "-movflags", "+faststart",
                                 "-f", "mp4", output},
        io::ChildProcess::Options{{}, m_log.path(), true});
}

VideoWriter::~VideoWriter() = default; // the child is stopped, then the temporaries removed

void VideoWriter::fail(const std::string& what)
{
    const int status = m_ffmpeg->wait();
    const std::string message = io::firstLine(m_log.path());
    throw io::WriteError(fmt::format("{}: {} ({}){}{}", m_video.target().string(), what, io::describeExit(status),
                                     message.empty() ? "" : ": ", message));
}

void VideoWriter::addFrame(const std::vector<std::uint8_t>& rgba)
{
    if (rgba.size() != m_frameBytes)
        throw io::WriteError("a frame of the wrong size");
    if (!m_ffmpeg->write(rgba.data(), rgba.size()))
        fail("ffmpeg stopped accepting frames");
}

void VideoWriter::finish()
{
    const int status = m_ffmpeg->wait();
    const std::string message = io::firstLine(m_log.path());
    if (status != 0)
        throw io::WriteError(fmt::format("{}: ffmpeg failed ({}){}{}", m_video.target().string(),
                                         io::describeExit(status), message.empty() ? "" : ": ", message));
    // ffmpeg exits 0 even when it could not write the video's end (a full disk), so neither its
    // status nor the file's existence says the video is whole: at -loglevel error it says
    // nothing unless something failed, and the file must read back as a complete MP4.
    if (!message.empty())
        throw io::WriteError(fmt::format("{}: ffmpeg reported an error (exit status 0): {}", m_video.target().string(),
                                         message));
    if (const std::string problem = mp4Problem(m_video.path()); !problem.empty())
        throw io::WriteError(fmt::format("{}: ffmpeg wrote an incomplete video: {}", m_video.target().string(), problem));
    m_video.commit();
}

} // namespace pba::render
