#pragma once
// Output files are written to a temporary name beside the target and renamed into place
// only when complete: a failed or interrupted run never leaves a truncated file under the
// requested name, and an existing file is replaced only on success.
#include <filesystem>
#include <fstream>

namespace pba::app {

class AtomicFile {
public:
    /// Opens the temporary file; throws UsageError naming the path if it cannot be written.
    explicit AtomicFile(std::filesystem::path target);
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;
    /// Removes the temporary file unless commit() succeeded.
    ~AtomicFile();

    std::ofstream& stream() { return m_stream; }
    const std::filesystem::path& temporaryPath() const { return m_temporary; }
    /// Flushes, closes and renames onto the target; throws RuntimeFailure on I/O errors.
    void commit();

private:
    std::filesystem::path m_target;
    std::filesystem::path m_temporary;
    std::ofstream m_stream;
    bool m_committed = false;
};

} // namespace pba::app
