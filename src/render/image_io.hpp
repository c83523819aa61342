#pragma once
// Frames to files: PNG through stb_image_write, video by piping raw frames to ffmpeg.
// Both write to a temporary name beside the target and rename it when complete.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace pba::render {

/// Writes RGBA8 pixels (top row first) as a PNG, atomically. Throws RenderError on failure.
void writePng(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgba);

/// An H.264 MP4 (yuv420p, plays in browsers) made by ffmpeg from raw RGBA frames.
class VideoWriter {
public:
    /// Throws RenderError if ffmpeg is missing (naming the Debian package) or cannot start.
    VideoWriter(std::filesystem::path target, int width, int height, int fps);
    ~VideoWriter(); ///< without finish(): stops ffmpeg and removes the partial file
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    void addFrame(const std::vector<std::uint8_t>& rgba);
    /// Closes the pipe, checks ffmpeg succeeded, and renames the video into place.
    void finish();

private:
    std::filesystem::path m_target;
    std::filesystem::path m_temporary;
    std::FILE* m_pipe = nullptr;
    std::size_t m_frameBytes;
};

/// True if `ffmpeg` is on the PATH.
bool ffmpegAvailable();

} // namespace pba::render
