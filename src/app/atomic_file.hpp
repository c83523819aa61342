#pragma once
// A text output (CSV, report) written through a stream into an io::Temporary beside the
// target and renamed into place only when complete and synced: a failed or interrupted run
// never leaves a truncated file under the requested name, and an existing file is replaced only
// on success.
#include <filesystem>
#include <fstream>

#include "io/output_file.hpp"

namespace pba::app {

class AtomicFile {
public:
    /// Checks the target (io::BadOutput if it is not a writable file path) and opens the temporary.
    explicit AtomicFile(const std::filesystem::path& target);
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ofstream& stream() { return m_stream; }
    const std::filesystem::path& temporaryPath() const { return m_temporary.path(); }
    /// Flushes, closes, syncs and renames onto the target; throws io::WriteError on I/O errors.
    void commit();

private:
    io::Temporary m_temporary;
    std::ofstream m_stream;
};

} // namespace pba::app
