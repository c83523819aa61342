#include "regular_file.hpp"

#include <algorithm>
#include <cerrno>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

namespace pba::scene_detail {

namespace {

std::string systemReason(int error) { return std::generic_category().message(error); }

const char* kindOf(mode_t mode)
{
    if (S_ISFIFO(mode))
        return "a FIFO";
    if (S_ISCHR(mode) || S_ISBLK(mode))
        return "a device";
    if (S_ISSOCK(mode))
        return "a socket";
    return "not a file of data";
}

} // namespace

std::string byteSize(std::uintmax_t bytes)
{
    if (bytes >= (1u << 20) && bytes % (1u << 20) == 0)
        return fmt::format("{} MiB", bytes >> 20);
    if (bytes >= (1u << 10) && bytes % (1u << 10) == 0)
        return fmt::format("{} KiB", bytes >> 10);
    return fmt::format("{} bytes", bytes);
}

RegularFile::RegularFile(const std::filesystem::path& path, std::uintmax_t maxBytes) : m_maxBytes(maxBytes)
{
    // O_NONBLOCK: opening a FIFO waits for a writer otherwise. What was opened is then checked
    // on the descriptor itself (fstat), so it cannot change between a check and the read.
    m_fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (m_fd < 0)
        throw std::runtime_error(fmt::format("cannot be opened ({})", systemReason(errno)));
    struct stat info {};
    if (::fstat(m_fd, &info) != 0) {
        const int error = errno;
        ::close(m_fd);
        throw std::runtime_error(fmt::format("cannot be examined ({})", systemReason(error)));
    }
    if (!S_ISREG(info.st_mode)) {
        ::close(m_fd);
        throw std::runtime_error(S_ISDIR(info.st_mode)
                                     ? std::string("is a folder, not a file")
                                     : fmt::format("is not a regular file ({})", kindOf(info.st_mode)));
    }
    m_identity = {static_cast<std::uint64_t>(info.st_dev), static_cast<std::uint64_t>(info.st_ino)};
    m_size = static_cast<std::uintmax_t>(info.st_size);
    if (m_size > maxBytes) {
        ::close(m_fd);
        throw std::runtime_error(fmt::format("is {} bytes, more than the {} a file here may have", m_size,
                                             byteSize(maxBytes)));
    }
}

RegularFile::~RegularFile() { ::close(m_fd); }

std::string RegularFile::read()
{
    // Up to one byte past the limit: a file that grew since it was opened is refused, not cut.
    std::string text(static_cast<std::size_t>(m_size) + 1, '\0');
    std::size_t filled = 0;
    while (true) {
        if (filled == text.size()) {
            if (text.size() > m_maxBytes)
                throw std::runtime_error(fmt::format("has grown past the {} a file here may have while being read",
                                                     byteSize(m_maxBytes)));
            text.resize(std::min<std::uintmax_t>(2 * text.size(), m_maxBytes + 1));
        }
        const ssize_t got = ::read(m_fd, text.data() + filled, text.size() - filled);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0)
            throw std::runtime_error(fmt::format("cannot be read ({})", systemReason(errno)));
        if (got == 0)
            break;
        filled += static_cast<std::size_t>(got);
    }
    text.resize(filled);
    return text;
}

} // namespace pba::scene_detail
