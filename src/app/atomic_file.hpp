#pragma once
// A text output (CSV, report) written through a stream into an io::Temporary beside the
// target and renamed into place only when complete and synced: a failed or interrupted run
// never leaves a truncated file under the requested name, and an existing file is replaced only
// on success.
#include <filesystem>
#include <fstream>
#include <string_view>

#include "io/output_file.hpp"

namespace pba::app {

class AtomicFile {
public:
    /// Checks the target (io::BadOutput if it is not a writable file path, naming `flag` when
    /// the temporary cannot be opened) and opens the temporary.
    explicit AtomicFile(const std::filesystem::path& target, std::string_view flag = {});
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

/// The file `requested` names (io::resolveOutputFile), with its temporary opened beside it and
/// removed again: a file written only once the work is done (a picture) is checked before the
/// work as sim's CSV is, which AtomicFile opens before the run. Throws io::BadOutput naming `flag`
/// and the path for a folder that cannot be written (read-only, no permission).
std::filesystem::path resolveWritableFile(std::string_view flag, const std::filesystem::path& requested);

} // namespace pba::app
