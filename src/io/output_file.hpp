#pragma once
// Outputs are written completely or not at all: into a temporary beside the target, synced to
// the disk, then renamed over it, so a full disk, a failed helper program or a signal leaves the
// previous file (or folder) untouched and no temporary behind.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pba::io {

/// The output path itself is wrong (a directory, a device, a missing folder): bad input.
class BadOutput : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Writing failed (a full disk, a helper program's error): not the user's input.
class WriteError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The file an output path names. A symbolic link is followed to its target, which is the file
/// replaced (the link stays a link). Throws BadOutput for an empty path, a path ending in '/'
/// (a folder's), a directory, anything that is not a regular file (a device such as /dev/null, a
/// FIFO, a socket) or a folder that does not exist, unless it is the last one of the path (its
/// parent exists): Temporary makes it.
std::filesystem::path resolveOutputFile(const std::filesystem::path& requested);

/// The same for a folder output: an existing folder (replaced as a whole) or a new one in an
/// existing folder, or in a missing one whose parent exists. Throws BadOutput otherwise.
std::filesystem::path resolveOutputFolder(const std::filesystem::path& requested);

/// A temporary file or folder beside its target (`TARGET.tmp-PID`), removed when this object
/// dies uncommitted and when the program is stopped by SIGINT, SIGTERM or SIGHUP. Makes the
/// target's folder if it is missing (the one folder the resolve functions let through).
class Temporary {
public:
    enum class Kind { File, Folder };
    Temporary(std::filesystem::path target, Kind kind);
    Temporary(const Temporary&) = delete;
    Temporary& operator=(const Temporary&) = delete;
    ~Temporary();

    const std::filesystem::path& path() const { return m_temporary; }
    const std::filesystem::path& target() const { return m_target; }
    /// Syncs the temporary's data to the disk and renames it onto the target (a folder target is
    /// swapped whole). Throws WriteError, leaving the target as it was.
    void commit();

private:
    std::filesystem::path m_target;
    std::filesystem::path m_temporary;
    Kind m_kind;
    bool m_committed = false;
};

/// Writes `bytes` to `target` (already resolved) completely or not at all; throws WriteError.
void writeFileAtomically(const std::filesystem::path& target, std::string_view bytes);

/// Writes `bytes` to a new file at `path` (inside a Temporary folder, which is synced as a
/// whole); throws WriteError.
void writeFile(const std::filesystem::path& path, std::string_view bytes);

/// Writes all of `bytes` to a file descriptor, through short writes and interruptions; false
/// on any error (errno says which).
bool writeAll(int fd, const void* bytes, std::size_t size);

/// From now on SIGINT, SIGTERM and SIGHUP (a closed terminal) remove every live Temporary and
/// stop every started child program, then end the program as the signal would. Call once, first thing in main(), before
/// any thread starts (threads inherit the blocked signals the watcher thread waits for).
void cleanUpOnSignals();

/// Used by ChildProcess: children to stop on a signal.
void registerChild(int pid);
void unregisterChild(int pid);

} // namespace pba::io
