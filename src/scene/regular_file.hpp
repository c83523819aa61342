#pragma once
// A file a scene names (a mesh), read safely: only a regular file is read, never a FIFO (which
// would wait for a writer forever) or a device (/dev/zero never ends), and never more than a
// limit, checked before anything is read.
#include <compare>
#include <cstdint>
#include <filesystem>
#include <string>

namespace pba::scene_detail {

/// Which file it is, however its path is spelt ("a.obj", "./a.obj", a link to it): its device
/// and inode.
struct FileIdentity {
    std::uint64_t device = 0;
    std::uint64_t inode = 0;
    auto operator<=>(const FileIdentity&) const = default;
};

class RegularFile {
public:
    /// Opens `path` without blocking and checks what it opened. std::runtime_error "is a folder",
    /// "is not a regular file (...)", "cannot be opened (reason)" or "is N bytes, more than ...".
    RegularFile(const std::filesystem::path& path, std::uintmax_t maxBytes);
    ~RegularFile();
    RegularFile(const RegularFile&) = delete;
    RegularFile& operator=(const RegularFile&) = delete;

    const FileIdentity& identity() const { return m_identity; }
    /// The whole file. std::runtime_error if reading fails or the file has grown past the limit.
    std::string read();

private:
    int m_fd = -1;
    FileIdentity m_identity;
    std::uintmax_t m_size = 0;
    std::uintmax_t m_maxBytes = 0;
};

/// "256 MiB", "64 KiB", "100 bytes": a limit as the messages give it.
std::string byteSize(std::uintmax_t bytes);

} // namespace pba::scene_detail
