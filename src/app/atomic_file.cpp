#include "atomic_file.hpp"

#include <unistd.h>

#include <fmt/format.h>

#include "command.hpp"

namespace pba::app {

AtomicFile::AtomicFile(std::filesystem::path target) : m_target(std::move(target))
{
    if (std::filesystem::is_directory(m_target))
        throw UsageError(fmt::format("{}: is a directory, expected a file path", m_target.string()));
    m_temporary = m_target;
    m_temporary += fmt::format(".tmp-{}", ::getpid());
    m_stream.open(m_temporary, std::ios::binary | std::ios::trunc);
    if (!m_stream)
        throw UsageError(fmt::format("{}: cannot be written (does the directory exist, is it writable?)",
                                     m_target.string()));
}

AtomicFile::~AtomicFile()
{
    if (!m_committed) {
        m_stream.close();
        std::error_code ignored;
        std::filesystem::remove(m_temporary, ignored);
    }
}

void AtomicFile::commit()
{
    m_stream.flush();
    const bool ok = static_cast<bool>(m_stream);
    m_stream.close();
    if (!ok)
        throw RuntimeFailure(fmt::format("{}: write failed (disk full?)", m_target.string()));
    std::error_code ec;
    std::filesystem::rename(m_temporary, m_target, ec);
    if (ec)
        throw RuntimeFailure(fmt::format("{}: cannot be replaced: {}", m_target.string(), ec.message()));
    m_committed = true;
}

} // namespace pba::app
