#pragma once
// Outputs are written completely or not at all: into a temporary beside the target, synced to
// the disk, then renamed over it, so a full disk, a failed helper program or a signal leaves the
// previous file untouched and no temporary behind. Folder outputs build on this
// (folder_output.hpp).
#include <filesystem>
#include <mutex>
#include <optional>
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

/// The folder a file is in: "." for a bare name.
std::filesystem::path folderOf(const std::filesystem::path& file);

/// The file an output path names. A symbolic link is followed to its target, which is the file
/// replaced (the link stays a link). Throws BadOutput for an empty path, a path ending in '/'
/// (a folder's), a directory, anything that is not a regular file (a device such as /dev/null, a
/// FIFO, a socket), a file that pba did not write or that changed since (its folder's manifest,
/// output_manifest.hpp, says) or a folder that does not exist, unless it is the last one of the
/// path (its parent exists): Temporary makes it.
std::filesystem::path resolveOutputFile(const std::filesystem::path& requested);

/// The same for a folder output: an existing folder or a new one in an existing folder, or in a
/// missing one whose parent exists. Throws BadOutput otherwise.
std::filesystem::path resolveOutputFolder(const std::filesystem::path& requested);

/// A temporary file or folder beside its target (`TARGET.tmp-PID`), removed when this object
/// dies uncommitted and when the program is stopped by SIGINT, SIGTERM or SIGHUP. Makes the
/// target's folder if it is missing (the one folder resolveOutputFile lets through), and removes
/// it again with the temporary while it is empty.
class Temporary {
public:
    enum class Kind { File, Folder };
    Temporary(std::filesystem::path target, Kind kind);
    Temporary(const Temporary&) = delete;
    Temporary& operator=(const Temporary&) = delete;
    ~Temporary();

    const std::filesystem::path& path() const { return m_temporary; }
    const std::filesystem::path& target() const { return m_target; }
    /// Syncs the temporary's data to the disk and renames it onto the target, which for a folder
    /// must be missing or empty (folder outputs are FolderOutput's). A file the user named is
    /// listed in its folder's manifest (publishListed). Throws WriteError, or BadOutput if the
    /// target became the user's meanwhile, leaving the target as it was.
    void commit();

private:
    bool listedWhenCommitted() const;

    std::filesystem::path m_target;
    std::filesystem::path m_temporary;
    Kind m_kind;
    std::optional<std::filesystem::path> m_madeFolder;
    bool m_committed = false;
};

/// Writes `bytes` to `target` (already resolved) completely or not at all; throws WriteError.
void writeFileAtomically(const std::filesystem::path& target, std::string_view bytes);

/// Writes `bytes` to a new file at `path` (inside a folder that is synced as a whole before its
/// files are published, such as FolderOutput's); throws WriteError.
void writeFile(const std::filesystem::path& path, std::string_view bytes);

/// Writes all of `bytes` to a file descriptor, through short writes and interruptions; false
/// on any error (errno says which).
bool writeAll(int fd, const void* bytes, std::size_t size);

/// fsyncs a file, or a folder's entries; false on an error (errno says which). A folder's files
/// are synced one by one with syncTree.
bool syncToDisk(const std::filesystem::path& path, bool directory);
bool syncTree(const std::filesystem::path& folder);

/// From now on SIGINT, SIGTERM and SIGHUP (a closed terminal) remove every live Temporary, stop
/// every started child program and remove the folders an output made that are still empty, then
/// end the program as the signal would. Call once, first thing in main(), before any thread
/// starts (threads inherit the blocked signals the watcher thread waits for).
void cleanUpOnSignals();

/// While the lock lives a signal's clean-up waits: held by a commit made of several renames
/// (FolderOutput's), so a signal never stops it half way.
std::unique_lock<std::mutex> deferSignals();

/// Used by ChildProcess: children to stop on a signal.
void registerChild(int pid);
void unregisterChild(int pid);

/// Used by FolderOutput: a folder it made, removed on a signal if nothing is in it.
void registerMadeFolder(const std::filesystem::path& folder);
void unregisterMadeFolder(const std::filesystem::path& folder);

} // namespace pba::io
