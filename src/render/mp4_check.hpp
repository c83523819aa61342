#pragma once
// ffmpeg can exit 0 after failing to write the end of a video (a full disk: "Error writing
// trailer"), leaving a file without its index. Before such a file may replace a good one, its
// top-level MP4 boxes are walked: their sizes must add up to the file's, and the file type
// (ftyp), the index (moov) and the media data (mdat) must be there (ISO/IEC 14496-12, 4.2).
#include <filesystem>
#include <string>

namespace pba::render {

/// "" for a complete MP4, else what is wrong with it, in a few words for a one-line message.
std::string mp4Problem(const std::filesystem::path& file);

} // namespace pba::render
