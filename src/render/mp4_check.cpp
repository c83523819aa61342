#include "mp4_check.hpp"

#include <array>
#include <cstdint>
#include <fstream>

#include <fmt/format.h>

namespace pba::render {

namespace {

std::uint64_t bigEndian(const unsigned char* bytes, int count)
{
    std::uint64_t value = 0;
    for (int i = 0; i < count; ++i)
        value = value << 8 | bytes[i];
    return value;
}

} // namespace

std::string mp4Problem(const std::filesystem::path& file)
{
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(file, ec);
    std::ifstream in(file, std::ios::binary);
    if (ec || !in)
        return "it cannot be read back";
    if (size == 0)
        return "it is empty";
    bool moov = false, mdat = false;
    for (std::uint64_t at = 0; at < size;) {
        // A box: a 32-bit size and a type; size 1 means a 64-bit size follows, 0 "to the end".
        std::array<unsigned char, 16> header{};
        const std::uint64_t left = size - at;
        if (left < 8 || !in.seekg(std::streamoff(at)) || !in.read(reinterpret_cast<char*>(header.data()), 8))
            return fmt::format("it ends inside a box header at byte {}", at);
        const std::string type(reinterpret_cast<const char*>(header.data()) + 4, 4);
        std::uint64_t boxSize = bigEndian(header.data(), 4), headerSize = 8;
        if (boxSize == 1) {
            if (left < 16 || !in.read(reinterpret_cast<char*>(header.data()) + 8, 8))
                return fmt::format("it ends inside a box header at byte {}", at);
            boxSize = bigEndian(header.data() + 8, 8);
            headerSize = 16;
        } else if (boxSize == 0) {
            boxSize = left;
        }
        if (boxSize < headerSize || boxSize > left)
            return fmt::format("its '{}' box at byte {} claims {} bytes, {} are left: the file is cut short", type,
                               at, boxSize, left);
        if (at == 0 && type != "ftyp")
            return "it does not start with an MP4 file type box";
        moov = moov || type == "moov";
        mdat = mdat || type == "mdat";
        at += boxSize;
    }
    if (!moov)
        return "it has no index (moov box), which ffmpeg writes last";
    return mdat ? "" : "it has no media data (mdat box)";
}

} // namespace pba::render
