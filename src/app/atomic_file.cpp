#include "atomic_file.hpp"

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

namespace pba::app {

AtomicFile::AtomicFile(const std::filesystem::path& target, std::string_view flag)
    : m_temporary(io::resolveOutputFile(target), io::Temporary::Kind::File)
{
    errno = 0;
    m_stream.open(m_temporary.path(), std::ios::binary | std::ios::trunc);
    if (!m_stream)
        throw io::BadOutput(fmt::format("{}{}: cannot be written ({})", flag.empty() ? "" : fmt::format("{}: ", flag),
                                        target.string(),
                                        errno != 0 ? std::strerror(errno) : "is the folder writable?"));
}

std::filesystem::path resolveWritableFile(std::string_view flag, const std::filesystem::path& requested)
{
    const std::filesystem::path target = io::resolveOutputFile(requested);
    const AtomicFile probe(requested, flag); // uncommitted: its temporary is removed again
    return target;
}

void AtomicFile::commit()
{
    m_stream.flush();
    const bool ok = static_cast<bool>(m_stream);
    m_stream.close();
    if (!ok || m_stream.fail())
        throw io::WriteError(fmt::format("{}: write failed (disk full?)", m_temporary.target().string()));
    m_temporary.commit();
}

} // namespace pba::app
