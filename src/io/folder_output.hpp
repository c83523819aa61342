#pragma once
// A folder output (`render --out DIR/`, `compare --out DIR`) writes and replaces only pba's own
// files in the folder and leaves everything else in it alone. The new files are written into a
// staging folder inside it (`DIR/.pba-staging.tmp-PID`, so `--out .` needs no writable parent),
// synced, then renamed into place together; pba's files of an earlier run that this one did not
// write again (the frames of a longer run) are removed. Which files are pba's, the folder's
// manifest says (output_manifest.hpp). A file with a name this output writes or may leave stale
// that pba did not write, or that changed since, would be replaced or left among the new files:
// the output is refused before any work is done, naming it.
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/output_file.hpp"
#include "io/output_manifest.hpp"

namespace pba::io {

class FolderOutput {
public:
    /// Whether a file name is one this output writes or may leave stale: its whole vocabulary,
    /// not only this run's (every frame_NNNNN.png, every plot a study can draw).
    using NamePredicate = std::function<bool(const std::string&)>;

    /// Resolves `requested` (resolveOutputFolder) and checks what is in it: throws BadOutput
    /// naming the first file with one of this output's names that pba did not write. Makes the
    /// folder if it is missing (and its parent, the one more resolveOutputFolder lets through),
    /// and the staging folder.
    FolderOutput(const std::filesystem::path& requested, NamePredicate owns);
    FolderOutput(const FolderOutput&) = delete;
    FolderOutput& operator=(const FolderOutput&) = delete;
    /// Uncommitted: the staging folder goes, and the folders made for it if they are empty.
    ~FolderOutput();

    /// Where the new files are written, under the names they will have in the folder.
    const std::filesystem::path& path() const { return m_staging->path(); }
    const std::filesystem::path& folder() const { return m_folder; }

    /// Syncs the new files, renames them into the folder, removes pba's stale files there and
    /// updates the manifest; a signal waits until this is done. Throws BadOutput if a file with
    /// one of this output's names appeared or changed meanwhile, WriteError if a write fails:
    /// the folder as it was, unless a rename itself fails half way (then each name holds its old
    /// or its new file, all listed as pba's).
    void commit();

private:
    /// What a file in the folder was when it was checked: a later change shows in one of these.
    struct Stamp {
        std::uintmax_t size = 0;
        long long mtimeNs = 0;
        unsigned long long inode = 0;
        bool operator==(const Stamp&) const = default;
    };
    /// Folders this output made, removed when it fails if nothing else went into them.
    struct MadeFolders {
        std::vector<std::filesystem::path> paths;
        bool keep = false;
        ~MadeFolders();
    };

    static std::optional<Stamp> stampOf(const std::filesystem::path& file);
    void checkFolder();
    void makeFolders();
    std::vector<ManifestEntry> newFiles() const;
    void recheckFolder() const;
    void publish(const std::vector<ManifestEntry>& written);

    std::filesystem::path m_folder;
    NamePredicate m_owns;
    OutputManifest m_manifest;                ///< as it was when checked
    std::map<std::string, Stamp> m_owned;     ///< pba's files of this output's names, as checked
    MadeFolders m_made;
    std::optional<Temporary> m_staging;       ///< after m_made: it goes first
};

} // namespace pba::io
