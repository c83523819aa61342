#pragma once
// Frames to files: PNG through stb_image_write, video by piping raw frames to ffmpeg (started
// from an argument vector, never a shell). Both are written completely or not at all (see
// io/output_file.hpp).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "io/child_process.hpp"
#include "io/output_file.hpp"

namespace pba::render {

/// RGBA8 pixels (top row first) as PNG bytes.
std::string encodePng(int width, int height, const std::vector<std::uint8_t>& rgba);

/// Writes RGBA8 pixels as a PNG at a resolved target, atomically; throws io::WriteError.
void writePng(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgba);

/// An H.264 MP4 (yuv420p, plays in browsers) made by ffmpeg from raw RGBA frames.
class VideoWriter {
public:
    /// `target` is resolved (io::resolveOutputFile). Throws io::WriteError if ffmpeg is missing
    /// (naming the Debian package) or cannot start.
    VideoWriter(const std::filesystem::path& target, int width, int height, int fps);
    /// Without finish(): stops ffmpeg; the partial file goes with the temporary.
    ~VideoWriter();
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    void addFrame(const std::vector<std::uint8_t>& rgba);
    /// Waits for ffmpeg, checks it succeeded (its exit status, its log and the file: see
    /// mp4_check.hpp), and renames the video into place; throws io::WriteError otherwise.
    void finish();

private:
    void fail(const std::string& what);

    io::Temporary m_video;
    io::Temporary m_log;
    std::size_t m_frameBytes;
    std::unique_ptr<io::ChildProcess> m_ffmpeg;
};

/// True if `ffmpeg` is on the PATH.
bool ffmpegAvailable();

} // namespace pba::render
