#pragma once
// Where rendered frames go: one PNG, numbered PNGs in a folder, or an MP4 through ffmpeg.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "io/folder_output.hpp"
#include "render/image_io.hpp"

namespace pba::app {

enum class OutputKind { Png, Mp4, Frames };

/// FILE.png, FILE.mp4, or a directory (a path ending in '/' or an existing directory).
/// Throws UsageError for anything else.
OutputKind outputKind(const std::string& out);
/// The path's extension in lower case (".png"), or empty.
std::string lowerExtension(const std::string& path);

/// frame_NNNNN.png (five digits or more): the names a folder of frames is made of.
bool isFrameName(const std::string& name);

class FrameSink {
public:
    /// Checks the output can be written before any rendering (io::BadOutput if not).
    FrameSink(OutputKind kind, const std::string& out, int width, int height, int fps);
    void add(const std::vector<std::uint8_t>& rgba);
    void finish();

private:
    OutputKind m_kind;
    std::filesystem::path m_out;              ///< a file output, resolved
    std::unique_ptr<io::FolderOutput> m_folder; ///< a folder of frames
    int m_width;
    int m_height;
    long m_count = 0;
    std::vector<std::uint8_t> m_last;
    std::unique_ptr<render::VideoWriter> m_video;
};

} // namespace pba::app
