#include "atomic_file.hpp"

#include <fmt/format.h>

namespace pba::app {

AtomicFile::AtomicFile(const std::filesystem::path& target)
    : m_temporary(io::resolveOutputFile(target), io::Temporary::Kind::File)
{
    m_stream.open(m_temporary.path(), std::ios::binary | std::ios::trunc);
    if (!m_stream)
        throw io::BadOutput(fmt::format("{}: cannot be written (is the folder writable?)", target.string()));
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
